// Second half of G, last step: g_i += s_i Σ_v for the three parameters i of each base vertex v,
// Σ_v the sums that reach it (scatter_sums.comp), which is then cleared. One thread per vertex.
#include "bindings.h"
#include "fixed_point.glsl"
#include "hash.glsl"

layout(local_size_x = 64) in;

#ifdef SUBDFIT_FULL_IMAGE
// Plain SPSA, for comparison only: the whole image's Δ (G's one sum) for every vertex.
layout(std430, binding = SUBDFIT_SSBO_FACE_DELTA) readonly buffer FaceDelta { uint faceDelta[]; };
#else
layout(std430, binding = SUBDFIT_SSBO_VERTEX_DELTA) buffer VertexDelta { uint vertexDelta[]; };
#endif
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SUM) buffer Gradient { uint gradient[]; };

uniform int uVertexCount;
uniform uint uCounter;
uniform uint uSeed;

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
#ifdef SUBDFIT_FULL_IMAGE
    float total = fromFixed(faceDelta[0], faceDelta[1]);
#else
    float total = fromFixed(vertexDelta[2 * v], vertexDelta[2 * v + 1]);
    vertexDelta[2 * v] = 0u;
    vertexDelta[2 * v + 1] = 0u;
#endif
    if (total == 0.0) return;
    for (uint c = 0u; c < 3u; ++c) {
        uint i = 3u * uint(v) + c;
        uvec2 updated = addFixed(uvec2(gradient[2u * i], gradient[2u * i + 1u]),
                                 toFixed(total * perturbationSign(i, uCounter, uSeed)));
        gradient[2u * i] = updated.x;
        gradient[2u * i + 1u] = updated.y;
    }
}
