// Every point the patches use, from the control points: base points are copied, refined and
// local points are Σ_k w_k x_k over base vertices (OpenSubdiv stencils, factorized to level 0).
// SUBDFIT_SECOND_SET: a second set of control points beside the first (θ− beside θ+), summed in
// the same loop, so a step's two sets read each stencil's entries once.
#include "bindings.h"

layout(local_size_x = 128) in;

// The control points, a point per texel (RGB32F): one gather each, not three loads.
layout(binding = SUBDFIT_UNIT_STENCIL_SOURCE) uniform samplerBuffer source;
layout(std430, binding = SUBDFIT_SSBO_STENCIL_OFFSETS) readonly buffer Offsets { int stencilOffsets[]; };
// Each stencil entry's (source index, weight's bits) in one texel (RG32UI): one fetch.
layout(binding = SUBDFIT_UNIT_STENCIL_ENTRIES) uniform usamplerBuffer stencilEntries;
layout(std430, binding = SUBDFIT_SSBO_POINTS) writeonly buffer Points { float points[]; };
#ifdef SUBDFIT_SECOND_SET
layout(binding = SUBDFIT_UNIT_STENCIL_SECOND_SOURCE) uniform samplerBuffer secondSource;
layout(std430, binding = SUBDFIT_SSBO_SECOND_POINTS) writeonly buffer SecondPoints { float secondPoints[]; };
#endif

uniform int uBaseCount;
uniform int uPointCount;

vec3 sourcePoint(int i) { return texelFetch(source, i).xyz; }
#ifdef SUBDFIT_SECOND_SET
vec3 secondSourcePoint(int i) { return texelFetch(secondSource, i).xyz; }
#endif

void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i >= uPointCount) return;
    vec3 p = vec3(0.0);
#ifdef SUBDFIT_SECOND_SET
    vec3 q = vec3(0.0);
#endif
    if (i < uBaseCount) {
        p = sourcePoint(i);
#ifdef SUBDFIT_SECOND_SET
        q = secondSourcePoint(i);
#endif
    } else {
        int s = i - uBaseCount;
        for (int k = stencilOffsets[s]; k < stencilOffsets[s + 1]; ++k) {
            uvec2 entry = texelFetch(stencilEntries, k).xy;
            int from = int(entry.x);
            float weight = uintBitsToFloat(entry.y);
            p += weight * sourcePoint(from);
#ifdef SUBDFIT_SECOND_SET
            q += weight * secondSourcePoint(from);
#endif
        }
    }
    points[3 * i] = p.x;
    points[3 * i + 1] = p.y;
    points[3 * i + 2] = p.z;
#ifdef SUBDFIT_SECOND_SET
    secondPoints[3 * i] = q.x;
    secondPoints[3 * i + 1] = q.y;
    secondPoints[3 * i + 2] = q.z;
#endif
}
