// The tessellation's vertices, one thread each: the surface point at (i/L, j/L) of its patch,
// where L = max(1, T / 2^depth) segments per patch edge (render::PatchTessellation). One pass
// per patch kind, like the basis it evaluates; the draw then rasterises plain triangles.
#include "bindings.h"
#include "osd_patch_basis"
#ifdef SUBDFIT_DISPLACEMENT
#include "maps.glsl"
#endif
#include "surface_point.glsl"

layout(local_size_x = 64) in;

// Per vertex: its patch, and i | j << 8 | L << 16.
layout(std430, binding = SUBDFIT_SSBO_TESSELLATION_SAMPLES) readonly buffer Samples { ivec2 samples[]; };
// Per vertex, 16 floats: position, normal, ∂P/∂u, ∂P/∂v, ptex (u, v), ptex face (its int's bits).
layout(std430, binding = SUBDFIT_SSBO_SURFACE_VERTICES) writeonly buffer SurfaceVertices { float surfaceVertices[]; };

uniform int uFirstSample;
uniform int uSampleCount;

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= uSampleCount) return;
    k += uFirstSample;
    ivec2 sample_ = samples[k];
    float level = float(sample_.y >> 16);
    vec2 st = vec2(float(sample_.y & 0xff), float((sample_.y >> 8) & 0xff)) / level;
    SurfacePoint p = surfacePoint(sample_.x, st);
    float values[16] = float[16](p.position.x, p.position.y, p.position.z, p.normal.x, p.normal.y, p.normal.z,
                                 p.tangentU.x, p.tangentU.y, p.tangentU.z, p.tangentV.x, p.tangentV.y, p.tangentV.z,
                                 p.ptexUv.x, p.ptexUv.y, intBitsToFloat(p.ptexFace), 0.0);
    for (int c = 0; c < 16; ++c) surfaceVertices[16 * k + c] = values[c];
}
