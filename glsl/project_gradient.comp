// Keeps a fraction of the tangential part of the (preconditioned) vertex gradient, in place:
//   g' = g − (1 − uKeep) · P g,
// with P the projection onto the tangent plane (normal from the face corners at the vertex) for a
// surface vertex, onto the chain direction for a crease vertex, and 0 for a fixed one. The images
// constrain a control vertex along the surface normal; what they say along the surface is mostly
// noise, and it is what lets a cage slide and crumple while its surface improves.
#include "bindings.h"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) readonly buffer Theta { float x[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) buffer Gradient { float g[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_MODES) readonly buffer Modes { int modes[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_OFFSETS) readonly buffer Offsets { int offsets[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_INDICES) readonly buffer Neighbours { int neighbours[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_CORNER_OFFSETS) readonly buffer CornerOffsets { int cornerOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_RELAX_CORNERS) readonly buffer Corners { int corners[]; };

uniform int uVertexCount;
uniform float uKeep;

vec3 point(int v) { return vec3(x[3 * v], x[3 * v + 1], x[3 * v + 2]); }

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount || modes[v] == 2) return;
    vec3 p = point(v);
    vec3 d = vec3(g[3 * v], g[3 * v + 1], g[3 * v + 2]);
    vec3 tangential = vec3(0.0);
    if (modes[v] == 1) {
        vec3 along = point(neighbours[offsets[v + 1] - 1]) - point(neighbours[offsets[v]]);
        float l = length(along);
        if (l > 0.0) tangential = dot(d, along / l) * (along / l);
    } else {
        vec3 n = vec3(0.0);
        for (int k = cornerOffsets[v]; k < cornerOffsets[v + 1]; ++k)
            n += cross(point(corners[2 * k + 1]) - p, point(corners[2 * k]) - p);
        float l = length(n);
        if (l > 0.0) tangential = d - dot(d, n / l) * (n / l);
    }
    d -= (1.0 - uKeep) * tangential;
    g[3 * v] = d.x;
    g[3 * v + 1] = d.y;
    g[3 * v + 2] = d.z;
}
