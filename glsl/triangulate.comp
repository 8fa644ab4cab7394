// Each quad of the tessellation split into two triangles along its shorter diagonal on the
// evaluated surface, one thread per quad: a split fixed in the patch's domain leans every facet
// of a displaced surface the same way. SUBDFIT_SURFACE_PAIR: a second surface's quads beside
// the first's (θ− beside θ+).
#include "bindings.h"

layout(local_size_x = 64) in;

// Read as buffer textures (a gather, where llvmpipe loads storage lane after lane); the two
// triangles written as three pairs of indices.
layout(binding = SUBDFIT_UNIT_TESSELLATION_QUADS) uniform usamplerBuffer quads;
layout(binding = SUBDFIT_UNIT_SURFACE_VERTICES) uniform samplerBuffer surfaceVertices;
layout(std430, binding = SUBDFIT_SSBO_SURFACE_TRIANGLES) writeonly buffer Triangles { uvec2 triangles[]; };
#ifdef SUBDFIT_SURFACE_PAIR
layout(binding = SUBDFIT_UNIT_SECOND_SURFACE_VERTICES) uniform samplerBuffer secondSurfaceVertices;
layout(std430, binding = SUBDFIT_SSBO_SECOND_SURFACE_TRIANGLES) writeonly buffer SecondTriangles { uvec2 secondTriangles[]; };
#endif

uniform int uQuadCount;

vec3 position(samplerBuffer vertices, uint v) { return texelFetch(vertices, int(4u * v)).xyz; }

// Quad c's two triangles, split along its shorter diagonal on `vertices`.
uvec2[3] split(samplerBuffer vertices, uvec4 c) {
    vec3 d02 = position(vertices, c.z) - position(vertices, c.x), d13 = position(vertices, c.w) - position(vertices, c.y);
    bool first = dot(d02, d02) <= dot(d13, d13);
    return uvec2[3](c.xy, first ? c.zx : c.wy, c.zw);
}

void main() {
    int q = int(gl_GlobalInvocationID.x);
    if (q >= uQuadCount) return;
    uvec4 c = texelFetch(quads, q);
    uvec2 pairs[3] = split(surfaceVertices, c);
    for (int k = 0; k < 3; ++k) triangles[3 * q + k] = pairs[k];
#ifdef SUBDFIT_SURFACE_PAIR
    pairs = split(secondSurfaceVertices, c);
    for (int k = 0; k < 3; ++k) secondTriangles[3 * q + k] = pairs[k];
#endif
}
