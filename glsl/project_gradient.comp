// Keeps a fraction of the tangential part of the (preconditioned) vertex gradient, in place:
//   g' = g − (1 − uKeep) · P g,
// with P the projection of tangent_frame.glsl. The images constrain a control vertex along the
// surface normal; what they say along the surface is mostly noise, and it is what lets a cage
// slide and crumple while its surface improves.
#include "bindings.h"
#include "tangent_frame.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) readonly buffer Theta { float x[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) buffer Gradient { float g[]; };

uniform int uVertexCount;
uniform float uKeep;

vec3 point(int v) { return vec3(x[3 * v], x[3 * v + 1], x[3 * v + 2]); }

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
    vec3 d = vec3(g[3 * v], g[3 * v + 1], g[3 * v + 2]);
    d -= (1.0 - uKeep) * tangentialPart(v, d);
    g[3 * v] = d.x;
    g[3 * v + 1] = d.y;
    g[3 * v + 2] = d.z;
}
