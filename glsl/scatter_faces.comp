// Second half of G: g_i += s_i Σ_{f ∋ v} faceDelta[f] for each parameter i of base vertex v,
// one thread per vertex (so no atomics), over the ptex faces whose stencils reach v.
#include "bindings.h"
#include "hash.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_FACE_DELTA) readonly buffer FaceDelta { float faceDelta[]; };
layout(std430, binding = SUBDFIT_SSBO_VERTEX_FACE_OFFSETS) readonly buffer Offsets { int vertexFaceOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_VERTEX_FACE_INDICES) readonly buffer Indices { int vertexFaceIndices[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT) buffer Gradient { float gradient[]; };

uniform int uVertexCount;
uniform uint uCounter;
uniform uint uSeed;

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
#ifdef SUBDFIT_FULL_IMAGE
    float sum = faceDelta[0];  // plain SPSA: the whole image's Δ for every vertex
#else
    float sum = 0.0;
    for (int k = vertexFaceOffsets[v]; k < vertexFaceOffsets[v + 1]; ++k) sum += faceDelta[vertexFaceIndices[k]];
#endif
    if (sum == 0.0) return;
    for (uint c = 0u; c < 3u; ++c) {
        uint i = 3u * uint(v) + c;
        gradient[i] += sum * perturbationSign(i, uCounter, uSeed);
    }
}
