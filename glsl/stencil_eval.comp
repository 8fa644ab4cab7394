// Every point the patches use, from the control points: base points are copied, refined and
// local points are Σ_k w_k x_k over base vertices (OpenSubdiv stencils, factorized to level 0).
#include "bindings.h"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_STENCIL_SOURCE) readonly buffer Source { float source[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_OFFSETS) readonly buffer Offsets { int stencilOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_INDICES) readonly buffer Indices { int stencilIndices[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_WEIGHTS) readonly buffer Weights { float stencilWeights[]; };
layout(std430, binding = SUBDFIT_SSBO_POINTS) writeonly buffer Points { float points[]; };

uniform int uBaseCount;
uniform int uPointCount;

vec3 sourcePoint(int i) { return vec3(source[3 * i], source[3 * i + 1], source[3 * i + 2]); }

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uPointCount) return;
    vec3 p = vec3(0.0);
    if (i < uBaseCount) {
        p = sourcePoint(i);
    } else {
        int s = i - uBaseCount;
        for (int k = stencilOffsets[s]; k < stencilOffsets[s + 1]; ++k)
            p += stencilWeights[k] * sourcePoint(stencilIndices[k]);
    }
    points[3 * i] = p.x;
    points[3 * i + 1] = p.y;
    points[3 * i + 2] = p.z;
}
