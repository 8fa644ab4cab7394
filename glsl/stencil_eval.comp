// Every point the patches use, from the control points: base points are copied, refined and
// local points are Σ_k w_k x_k over base vertices (OpenSubdiv stencils, factorized to level 0).
// The second row of work groups does the same for a second set of control points (θ− beside θ+),
// so that a step's two sets cost one dispatch.
#include "bindings.h"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_STENCIL_SOURCE) readonly buffer Source { float source[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_SECOND_SOURCE) readonly buffer SecondSource { float secondSource[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_OFFSETS) readonly buffer Offsets { int stencilOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_INDICES) readonly buffer Indices { int stencilIndices[]; };
layout(std430, binding = SUBDFIT_SSBO_STENCIL_WEIGHTS) readonly buffer Weights { float stencilWeights[]; };
layout(std430, binding = SUBDFIT_SSBO_POINTS) writeonly buffer Points { float points[]; };
layout(std430, binding = SUBDFIT_SSBO_SECOND_POINTS) writeonly buffer SecondPoints { float secondPoints[]; };

uniform int uBaseCount;
uniform int uPointCount;

bool second = gl_WorkGroupID.y == 1u;

vec3 sourcePoint(int i) {
    return second ? vec3(secondSource[3 * i], secondSource[3 * i + 1], secondSource[3 * i + 2])
                  : vec3(source[3 * i], source[3 * i + 1], source[3 * i + 2]);
}

void writePoint(int i, vec3 p) {
    if (second) {
        secondPoints[3 * i] = p.x;
        secondPoints[3 * i + 1] = p.y;
        secondPoints[3 * i + 2] = p.z;
    } else {
        points[3 * i] = p.x;
        points[3 * i + 1] = p.y;
        points[3 * i + 2] = p.z;
    }
}

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
    writePoint(i, p);
}
