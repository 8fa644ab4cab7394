// P: θ± = θ ± s⊙ε, one thread per parameter; s from the stateless hash, so G can recompute it.
#include "bindings.h"
#include "hash.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) readonly buffer Theta { float theta[]; };
layout(std430, binding = SUBDFIT_SSBO_THETA_PLUS) writeonly buffer ThetaPlus { float thetaPlus[]; };
layout(std430, binding = SUBDFIT_SSBO_THETA_MINUS) writeonly buffer ThetaMinus { float thetaMinus[]; };

uniform uint uCount;
uniform uint uCounter;
uniform uint uSeed;
uniform float uEpsilon;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uCount) return;
    float delta = perturbationSign(i, uCounter, uSeed) * uEpsilon;
    thetaPlus[i] = theta[i] + delta;
    thetaMinus[i] = theta[i] - delta;
}
