// Each quad of the tessellation split into two triangles along its shorter diagonal on the
// evaluated surface, one thread per quad: a split fixed in the patch's domain leans every facet
// of a displaced surface the same way.
#include "bindings.h"

layout(local_size_x = 64) in;

// Read as buffer textures (a gather, where llvmpipe loads storage lane after lane); the two
// triangles written as three pairs of indices.
layout(binding = SUBDFIT_UNIT_TESSELLATION_QUADS) uniform usamplerBuffer quads;
layout(binding = SUBDFIT_UNIT_SURFACE_VERTICES) uniform samplerBuffer surfaceVertices;
layout(std430, binding = SUBDFIT_SSBO_SURFACE_TRIANGLES) writeonly buffer Triangles { uvec2 triangles[]; };

uniform int uQuadCount;

vec3 position(uint v) { return texelFetch(surfaceVertices, int(4u * v)).xyz; }

void main() {
    int q = int(gl_GlobalInvocationID.x);
    if (q >= uQuadCount) return;
    uvec4 c = texelFetch(quads, q);
    vec3 d02 = position(c.z) - position(c.x), d13 = position(c.w) - position(c.y);
    bool first = dot(d02, d02) <= dot(d13, d13);
    triangles[3 * q] = c.xy;
    triangles[3 * q + 1] = first ? c.zx : c.wy;
    triangles[3 * q + 2] = c.zw;
}
