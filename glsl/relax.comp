// Tangential relaxation of the cage (fit/cage_relaxation.h): one thread per vertex,
//   x' = x + rate · P (c + r − x),   c = the centroid of the vertices it averages,
// r = where the vertex sat relative to that centroid in the start cage, low-passed,
// with P the projection of tangent_frame.glsl. Reads θ, writes
// the scratch buffer (Jacobi: every vertex sees its neighbours' old positions).
#include "bindings.h"
#include "tangent_frame.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_SMOOTH_IN) readonly buffer In { float x[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer Out { float y[]; };
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
    if (end > begin) {
        vec3 sum = vec3(0.0);
        for (int k = begin; k < end; ++k) sum += point(neighbours[k]);
        vec3 d = sum / float(end - begin) + vec3(rest[3 * v], rest[3 * v + 1], rest[3 * v + 2]) - p;
        move = tangentialPart(v, d);
    }
    p += uRate * move;
    y[3 * v] = p.x;
    y[3 * v + 1] = p.y;
    y[3 * v + 2] = p.z;
}
