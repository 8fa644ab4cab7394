// Adam's second moment shared by a whole parameter group (the "uniform Adam" of Nicolet et al.,
// Large Steps in Inverse Rendering, 2021): v ← β2 v + (1 − β2) mean_i g̃_i². Per-parameter
// normalisation would undo the Laplacian preconditioner's smoothing, vertex by vertex; one
// scale for the group keeps the smoothed step smooth. One work group does the whole reduction.
#include "bindings.h"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) readonly buffer Gradient { float gradient[]; };
layout(std430, binding = SUBDFIT_SSBO_GROUP_MOMENT2) buffer GroupMoment2 { float groupMoment2; };

uniform uint uCount;
uniform float uBeta2;

shared float partial[256];

void main() {
    uint lane = gl_LocalInvocationIndex;
    float sum = 0.0;
    for (uint i = lane; i < uCount; i += 256u) {
        float g = gradient[i];
        if (!isnan(g) && !isinf(g)) sum += g * g;
    }
    partial[lane] = sum;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1u) {
        if (lane < stride) partial[lane] += partial[lane + stride];
        barrier();
    }
    if (lane == 0u) groupMoment2 = mix(partial[0] / float(max(uCount, 1u)), groupMoment2, uBeta2);
}
