// Adam (Kingma & Ba) on one parameter group, one thread per parameter. A non-finite gradient
// (which a sound pipeline never produces) is dropped rather than allowed to poison θ.
// SUBDFIT_ADAM_SHARED_MOMENT: one second moment for the group (see shared_moment.comp).
#include "bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) buffer Theta { float theta[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) readonly buffer Gradient { float gradient[]; };
layout(std430, binding = SUBDFIT_SSBO_MOMENT1) buffer Moment1 { float moment1[]; };
layout(std430, binding = SUBDFIT_SSBO_MOMENT2) buffer Moment2 { float moment2[]; };

uniform uint uCount;
uniform float uLearningRate;
uniform float uBeta1;
uniform float uBeta2;
uniform float uBiasCorrection1;  // 1 − β1^t
uniform float uBiasCorrection2;  // 1 − β2^t
uniform float uAdamEpsilon;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uCount) return;
    float g = gradient[i];
    if (isnan(g) || isinf(g)) g = 0.0;
    float m = mix(g, moment1[i], uBeta1);
    moment1[i] = m;
#ifdef SUBDFIT_ADAM_SHARED_MOMENT
    float v = moment2[0];  // updated for the whole group by shared_moment.comp
#else
    float v = mix(g * g, moment2[i], uBeta2);
    moment2[i] = v;
#endif
    theta[i] -= uLearningRate * (m / uBiasCorrection1) / (sqrt(v / uBiasCorrection2) + uAdamEpsilon);
}
