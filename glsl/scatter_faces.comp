// Second half of G: g_i += s_i Σ_{k ∋ v} faceDelta[k] for each parameter i of base vertex v,
// one thread per vertex (so no atomics), over the sums whose vertices include v (the ptex faces
// whose stencils reach v, and the adjacent face pairs either of whose faces it reaches), in the
// table's order: sums and gradient are fixed point (fixed_point.glsl), so a run repeats exactly.
#include "bindings.h"
#include "fixed_point.glsl"
#include "hash.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_FACE_DELTA) readonly buffer FaceDelta { uint faceDelta[]; };
layout(std430, binding = SUBDFIT_SSBO_VERTEX_SUM_OFFSETS) readonly buffer Offsets { int vertexSumOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_VERTEX_SUM_INDICES) readonly buffer Indices { int vertexSumIndices[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SUM) buffer Gradient { uint gradient[]; };

uniform int uVertexCount;
uniform uint uCounter;
uniform uint uSeed;

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
#ifdef SUBDFIT_FULL_IMAGE
    float sum = fromFixed(faceDelta[0], faceDelta[1]);  // plain SPSA: the whole image's Δ for every vertex
#else
    float sum = 0.0;
    for (int k = vertexSumOffsets[v]; k < vertexSumOffsets[v + 1]; ++k) {
        uint f = uint(vertexSumIndices[k]);
        sum += fromFixed(faceDelta[2u * f], faceDelta[2u * f + 1u]);
    }
#endif
    if (sum == 0.0) return;
    for (uint c = 0u; c < 3u; ++c) {
        uint i = 3u * uint(v) + c;
        uvec2 total = addFixed(uvec2(gradient[2u * i], gradient[2u * i + 1u]),
                               toFixed(sum * perturbationSign(i, uCounter, uSeed)));
        gradient[2u * i] = total.x;
        gradient[2u * i + 1u] = total.y;
    }
}
