// Each quad of the tessellation split into two triangles along its shorter diagonal on the
// evaluated surface, one thread per quad: a split fixed in the patch's domain leans every facet
// of a displaced surface the same way.
#include "bindings.h"

layout(local_size_x = 64) in;

layout(std430, binding = SUBDFIT_SSBO_TESSELLATION_QUADS) readonly buffer Quads { uvec4 quads[]; };
layout(std430, binding = SUBDFIT_SSBO_SURFACE_VERTICES) readonly buffer SurfaceVertices { float surfaceVertices[]; };
layout(std430, binding = SUBDFIT_SSBO_SURFACE_TRIANGLES) writeonly buffer Triangles { uint triangles[]; };

uniform int uQuadCount;

vec3 position(uint v) { return vec3(surfaceVertices[16u * v], surfaceVertices[16u * v + 1u], surfaceVertices[16u * v + 2u]); }

void main() {
    int q = int(gl_GlobalInvocationID.x);
    if (q >= uQuadCount) return;
    uvec4 c = quads[q];
    vec3 d02 = position(c.z) - position(c.x), d13 = position(c.w) - position(c.y);
    uint split[6] = dot(d02, d02) <= dot(d13, d13) ? uint[6](c.x, c.y, c.z, c.x, c.z, c.w)
                                                   : uint[6](c.x, c.y, c.w, c.y, c.z, c.w);
    for (int k = 0; k < 6; ++k) triangles[6 * q + k] = split[k];
}
