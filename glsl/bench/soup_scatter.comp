// G, second half, one thread per triangle: its 12 parameters get g_i = D s_i / 2ε_group, where D
// is the triangle's own Σ Δ_p (per-pixel) or the whole image's Σ_p Δ_p (full-image, reduced
// from the 256 slots in shared memory by every work group). 1 / s_i = s_i for signs ±1. Writes
// (not adds) the gradients, which adam.comp consumes and clears.
#include "soup_bindings.h"
#include "hash.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SOUP_SSBO_TRIANGLE_DELTA) readonly buffer TriangleDelta { float triangleDelta[]; };
layout(std430, binding = SUBDFIT_SOUP_SSBO_GRADIENT_POSITIONS) writeonly buffer GradientPositions {
    float gradientPositions[];
};
layout(std430, binding = SUBDFIT_SOUP_SSBO_GRADIENT_COLORS) writeonly buffer GradientColors { float gradientColors[]; };

uniform uint uTriangleCount;
uniform uint uCounter;
uniform uint uSeed;
uniform float uEpsilonPositions;
uniform float uEpsilonColors;

#ifdef SUBDFIT_SOUP_FULL_IMAGE
shared float partial[256];
#endif

void main() {
    uint triangle = gl_GlobalInvocationID.x;
#ifdef SUBDFIT_SOUP_FULL_IMAGE
    uint lane = gl_LocalInvocationIndex;
    partial[lane] = triangleDelta[lane];
    for (uint stride = 128u; stride > 0u; stride >>= 1u) {
        barrier();
        if (lane < stride) partial[lane] += partial[lane + stride];
    }
    barrier();
    float sum = partial[0];
#else
    if (triangle >= uTriangleCount) return;
    float sum = triangleDelta[triangle];
#endif
    if (triangle >= uTriangleCount) return;
    float positionScale = sum / (2.0 * uEpsilonPositions);
    for (uint k = 0u; k < 9u; ++k) {
        uint i = 9u * triangle + k;
        gradientPositions[i] = positionScale * perturbationSign(i, uCounter, uSeed ^ SUBDFIT_SOUP_SEED_POSITIONS);
    }
    float colorScale = sum / (2.0 * uEpsilonColors);
    for (uint k = 0u; k < 3u; ++k) {
        uint i = 3u * triangle + k;
        gradientColors[i] = colorScale * perturbationSign(i, uCounter, uSeed ^ SUBDFIT_SOUP_SEED_COLORS);
    }
}
