// Adam (Kingma & Ba) for one parameter: the step to subtract from θ_i given its gradient g and
// the second moment v that scales it (its own, or the group's: see shared_moment.comp). Updates
// the parameter's moments. A non-finite gradient (which a sound pipeline never produces) is
// dropped rather than allowed to poison θ.
// SUBDFIT_ADAM_NOISE_GATE: the step shrinks with the gradient's signal-to-noise ratio. Under
// white noise of variance σ², m̂ keeps a share k of it (k: uNoiseShare, from β1 and t), while
// v̂ ≈ μ² + σ²; so max(m̂² − c·k·v̂, 0) / m̂² is the positive-part James-Stein shrinkage of m̂
// towards 0 (c = uGateStrength). A parameter whose gradient is mostly noise barely moves
// instead of random-walking by a learning rate; one with a clear gradient keeps its full step.
// Declares the moment buffers and Adam's uniforms.
#ifndef SUBDFIT_ADAM_GLSL
#define SUBDFIT_ADAM_GLSL

layout(std430, binding = SUBDFIT_SSBO_MOMENT1) buffer Moment1 { float moment1[]; };
layout(std430, binding = SUBDFIT_SSBO_MOMENT2) buffer Moment2 { float moment2[]; };

uniform float uLearningRate;
uniform float uBeta1;
uniform float uBeta2;
uniform float uBiasCorrection1;  // 1 − β1^t
uniform float uBiasCorrection2;  // 1 − β2^t
uniform float uAdamEpsilon;
uniform float uNoiseShare;    // k = (1 − β1)(1 + β1^t) / ((1 + β1)(1 − β1^t)): white noise's share of v̂ in m̂²
uniform float uGateStrength;  // c

// A finite gradient, or 0.
float finiteOrZero(float g) { return isnan(g) || isinf(g) ? 0.0 : g; }

// `groupV`: the group's shared second moment; negative where each parameter uses its own.
float adamStep(uint i, float g, float groupV) {
    g = finiteOrZero(g);
    float m = mix(g, moment1[i], uBeta1);
    moment1[i] = m;
    float own = mix(g * g, moment2[i], uBeta2);
    moment2[i] = own;
    float v = groupV >= 0.0 ? groupV : own;
    float mHat = m / uBiasCorrection1;
    float step = uLearningRate * mHat / (sqrt(v / uBiasCorrection2) + uAdamEpsilon);
#ifdef SUBDFIT_ADAM_NOISE_GATE
    float noise = uGateStrength * uNoiseShare * own / uBiasCorrection2;
    step *= mHat * mHat > noise ? 1.0 - noise / (mHat * mHat) : 0.0;
#endif
    return step;
}

#endif
