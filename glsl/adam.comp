// Adam (Kingma & Ba) on one parameter group, one thread per parameter. A non-finite gradient
// (which a sound pipeline never produces) is dropped rather than allowed to poison θ.
// SUBDFIT_ADAM_SHARED_MOMENT: one second moment for the group (see shared_moment.comp) scales
// the step; each parameter's own second moment is still kept, for the noise gate.
// SUBDFIT_ADAM_NOISE_GATE: the step shrinks with the gradient's signal-to-noise ratio. Under
// white noise of variance σ², m̂ keeps a share k of it (k: uNoiseShare, from β1 and t), while
// v̂ ≈ μ² + σ²; so max(m̂² − c·k·v̂, 0) / m̂² is the positive-part James-Stein shrinkage of m̂
// towards 0 (c = uGateStrength). A parameter whose gradient is mostly noise barely moves
// instead of random-walking by a learning rate; one with a clear gradient keeps its full step.
#include "bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) buffer Theta { float theta[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) readonly buffer Gradient { float gradient[]; };
layout(std430, binding = SUBDFIT_SSBO_MOMENT1) buffer Moment1 { float moment1[]; };
layout(std430, binding = SUBDFIT_SSBO_MOMENT2) buffer Moment2 { float moment2[]; };
#ifdef SUBDFIT_ADAM_SHARED_MOMENT
layout(std430, binding = SUBDFIT_SSBO_GROUP_MOMENT2) readonly buffer GroupMoment2 { float groupMoment2; };
#endif

uniform uint uCount;
uniform float uLearningRate;
uniform float uBeta1;
uniform float uBeta2;
uniform float uBiasCorrection1;  // 1 − β1^t
uniform float uBiasCorrection2;  // 1 − β2^t
uniform float uAdamEpsilon;
uniform float uNoiseShare;    // k = (1 − β1)(1 + β1^t) / ((1 + β1)(1 − β1^t)): white noise's share of v̂ in m̂²
uniform float uGateStrength;  // c

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uCount) return;
    float g = gradient[i];
    if (isnan(g) || isinf(g)) g = 0.0;
    float m = mix(g, moment1[i], uBeta1);
    moment1[i] = m;
    float own = mix(g * g, moment2[i], uBeta2);
    moment2[i] = own;
#ifdef SUBDFIT_ADAM_SHARED_MOMENT
    float v = groupMoment2;  // updated for the whole group by shared_moment.comp
#else
    float v = own;
#endif
    float mHat = m / uBiasCorrection1;
    float step = uLearningRate * mHat / (sqrt(v / uBiasCorrection2) + uAdamEpsilon);
#ifdef SUBDFIT_ADAM_NOISE_GATE
    float noise = uGateStrength * uNoiseShare * own / uBiasCorrection2;
    step *= mHat * mHat > noise ? 1.0 - noise / (mHat * mHat) : 0.0;
#endif
    theta[i] -= step;
}
