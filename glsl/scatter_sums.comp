// Second half of G, first step: each sum Δ_k that G filled goes to every base vertex it reaches (a
// face's vertices; a pair's, the union of its two faces'), and is cleared. One thread per sum: on
// a dense cage most are empty in a step (a pixel sees neighbouring faces, while a pair is any two
// faces whose stencils share a vertex), so the work follows the pixels rather than the table.
// Added in fixed point (fixed_point.glsl), exactly, so their order does not matter.
#include "bindings.h"
#include "fixed_point.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = SUBDFIT_SSBO_FACE_DELTA) buffer FaceDelta { uint faceDelta[]; };
// The tables, read as buffer textures (a gather, where llvmpipe reads storage lane after lane).
layout(binding = SUBDFIT_UNIT_FACE_VERTEX_OFFSETS) uniform isamplerBuffer faceVertexOffsets;
layout(binding = SUBDFIT_UNIT_FACE_VERTICES) uniform isamplerBuffer faceVertices;
layout(binding = SUBDFIT_UNIT_PAIR_FACES) uniform isamplerBuffer pairFaces;  // (a, b) of each pair
layout(std430, binding = SUBDFIT_SSBO_VERTEX_DELTA) buffer VertexDelta { uint vertexDelta[]; };

uniform int uFaceCount;  // the faces' sums, then the pairs'
uniform int uSumCount;

void addToVertex(int v, uvec2 d) {
    uint low = atomicAdd(vertexDelta[2 * v], d.x);
    uint high = d.y + (low + d.x < low ? 1u : 0u);
    if (high != 0u) atomicAdd(vertexDelta[2 * v + 1], high);
}

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= uSumCount) return;
    uvec2 d = uvec2(faceDelta[2 * k], faceDelta[2 * k + 1]);
    if (d == uvec2(0u)) return;
    faceDelta[2 * k] = 0u;
    faceDelta[2 * k + 1] = 0u;
    bool pair = k >= uFaceCount;
    ivec2 faces = pair ? texelFetch(pairFaces, k - uFaceCount).xy : ivec2(k);
    // The two sorted vertex lists walked together: each vertex of the union once (a face's
    // sum walks its one list twice over, in step).
    int i = texelFetch(faceVertexOffsets, faces.x).x, iEnd = texelFetch(faceVertexOffsets, faces.x + 1).x;
    int j = texelFetch(faceVertexOffsets, faces.y).x, jEnd = texelFetch(faceVertexOffsets, faces.y + 1).x;
    while (i < iEnd || j < jEnd) {
        int va = i < iEnd ? texelFetch(faceVertices, i).x : 0x7fffffff;
        int vb = j < jEnd ? texelFetch(faceVertices, j).x : 0x7fffffff;
        int v = min(va, vb);
        addToVertex(v, d);
        if (va == v) ++i;
        if (vb == v) ++j;
    }
}
