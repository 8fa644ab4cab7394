// The tessellation's vertices, one thread each: the surface point at (i/L, j/L) of its patch,
// where L = max(1, T / 2^depth) segments per patch edge (render::PatchTessellation). One pass
// per patch kind, like the basis it evaluates; the draw then rasterises plain triangles.
// SUBDFIT_SURFACE_PAIR: two sets of points' surfaces at once (θ+ and θ−), one basis for both.
#include "bindings.h"
#include "osd_patch_basis"
#ifdef SUBDFIT_DISPLACEMENT
#include "maps.glsl"
#endif
#include "surface_point.glsl"

layout(local_size_x = 64) in;

// Per vertex: its patch, and i | j << 8 | L << 16.
layout(std430, binding = SUBDFIT_SSBO_TESSELLATION_SAMPLES) readonly buffer Samples { ivec2 samples[]; };
uniform int uFirstSample;
uniform int uSampleCount;

void main() {
    int k = int(gl_GlobalInvocationID.x);
    if (k >= uSampleCount) return;
    k += uFirstSample;
    ivec2 sample_ = samples[k];
    float level = float(sample_.y >> 16);
    vec2 st = vec2(float(sample_.y & 0xff), float((sample_.y >> 8) & 0xff)) / level;
#ifdef SUBDFIT_SURFACE_PAIR
    SurfacePoint first, second;
    surfacePoints(sample_.x, st, first, second);
    storeSurfaceVertex(k, first);
    storeSecondSurfaceVertex(k, second);
#else
    storeSurfaceVertex(k, surfacePoint(sample_.x, st));
#endif
}
