// Tangential relaxation of the cage (fit/cage_relaxation.h): one thread per vertex,
//   x' = x + rate · P (c + r − x),   c = the centroid of the vertices it averages,
// r = where the vertex sat relative to that centroid in the start cage, low-passed,
// with P the projection onto the tangent plane (normal from the face corners at x) for a surface
// vertex, onto the chain direction for a crease vertex, and 0 for a fixed one. Reads θ, writes
// the scratch buffer (Jacobi: every vertex sees its neighbours' old positions).
#include "bindings.h"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_SMOOTH_IN) readonly buffer In { float x[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer Out { float y[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_MODES) readonly buffer Modes { int modes[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_OFFSETS) readonly buffer Offsets { int offsets[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_INDICES) readonly buffer Neighbours { int neighbours[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_CORNER_OFFSETS) readonly buffer CornerOffsets { int cornerOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_CORNERS) readonly buffer Corners { int corners[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_REST) readonly buffer Rest { float rest[]; };

uniform int uVertexCount;
uniform float uRate;

vec3 point(int v) { return vec3(x[3 * v], x[3 * v + 1], x[3 * v + 2]); }

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
    vec3 p = point(v);
    vec3 move = vec3(0.0);
    int begin = offsets[v], end = offsets[v + 1];
    if (modes[v] != 2 && end > begin) {
        vec3 sum = vec3(0.0);
        for (int k = begin; k < end; ++k) sum += point(neighbours[k]);
        vec3 d = sum / float(end - begin) + vec3(rest[3 * v], rest[3 * v + 1], rest[3 * v + 2]) - p;
        if (modes[v] == 1) {
            vec3 along = point(neighbours[end - 1]) - point(neighbours[begin]);
            float l = length(along);
            move = l > 0.0 ? dot(d, along / l) * (along / l) : vec3(0.0);
        } else {
            vec3 n = vec3(0.0);
            for (int k = cornerOffsets[v]; k < cornerOffsets[v + 1]; ++k)
                n += cross(point(corners[2 * k + 1]) - p, point(corners[2 * k]) - p);
            float l = length(n);
            move = l > 0.0 ? d - dot(d, n / l) * (n / l) : vec3(0.0);
        }
    }
    p += uRate * move;
    y[3 * v] = p.x;
    y[3 * v + 1] = p.y;
    y[3 * v + 2] = p.z;
}
