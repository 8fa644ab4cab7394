// Second half of G: g_i += s_i Σ_{k ∋ v} faceDelta[k] for each parameter i of base vertex v, over
// the sums whose vertices include v (the ptex faces whose stencils reach v, and the adjacent face
// pairs either of whose faces it reaches): about a hundred on a quad mesh. SUBDFIT_SCATTER_LANES
// threads share a vertex's sums, so that no thread walks a long chain of dependent reads; the
// sums are added in fixed point (fixed_point.glsl), exactly, so their order does not matter and
// a run repeats exactly. One lane per vertex then writes its parameters (no atomics).
#include "bindings.h"
#include "fixed_point.glsl"
#include "hash.glsl"

layout(local_size_x = 128) in;
const uint kLanes = uint(SUBDFIT_SCATTER_LANES);  // a power of two dividing 128

layout(std430, binding = SUBDFIT_SSBO_FACE_DELTA) readonly buffer FaceDelta { uint faceDelta[]; };
layout(std430, binding = SUBDFIT_SSBO_VERTEX_SUM_OFFSETS) readonly buffer Offsets { int vertexSumOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_VERTEX_SUM_INDICES) readonly buffer Indices { int vertexSumIndices[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SUM) buffer Gradient { uint gradient[]; };

uniform int uVertexCount;
uniform uint uCounter;
uniform uint uSeed;

shared uvec2 partial[128];

void main() {
    uint lane = gl_LocalInvocationIndex % kLanes;
    int v = int(gl_GlobalInvocationID.x / kLanes);
    uvec2 sum = uvec2(0u);
    if (v < uVertexCount) {
#ifdef SUBDFIT_FULL_IMAGE
        // Plain SPSA: the whole image's Δ for every vertex.
        if (lane == 0u) sum = uvec2(faceDelta[0], faceDelta[1]);
#else
        for (int k = vertexSumOffsets[v] + int(lane); k < vertexSumOffsets[v + 1]; k += int(kLanes)) {
            uint f = uint(vertexSumIndices[k]);
            sum = addFixed(sum, uvec2(faceDelta[2u * f], faceDelta[2u * f + 1u]));
        }
#endif
    }
    partial[gl_LocalInvocationIndex] = sum;
    for (uint stride = kLanes / 2u; stride > 0u; stride /= 2u) {
        barrier();
        if (lane < stride) {
            sum = addFixed(sum, partial[gl_LocalInvocationIndex + stride]);
            partial[gl_LocalInvocationIndex] = sum;
        }
    }
    float total = fromFixed(sum.x, sum.y);
    if (lane != 0u || v >= uVertexCount || total == 0.0) return;
    for (uint c = 0u; c < 3u; ++c) {
        uint i = 3u * uint(v) + c;
        uvec2 updated = addFixed(uvec2(gradient[2u * i], gradient[2u * i + 1u]),
                                 toFixed(total * perturbationSign(i, uCounter, uSeed)));
        gradient[2u * i] = updated.x;
        gradient[2u * i + 1u] = updated.y;
    }
}
