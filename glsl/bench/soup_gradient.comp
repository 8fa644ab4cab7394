// G, first half, one thread per pixel: Δ_p = ‖I+_p − T_p‖² − ‖I−_p − T_p‖².
//
// Per-pixel (paper Eq. 5): g_i = Σ_{p covered by i's triangle in I+ or I−} Δ_p s_i / 2ε. s_i does
// not depend on the pixel, so each pixel adds Δ_p once to each triangle of the union {t+, t−}
// (once when they agree) and soup_scatter.comp multiplies by s_i / 2ε per parameter.
// Full-image (Eq. 1, SUBDFIT_SOUP_FULL_IMAGE): every pixel's Δ_p goes into one sum Σ_p Δ_p,
// spread over 256 slots by lane because one float taking every pixel would serialise.
#include "soup_bindings.h"
#include "atomics.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = SUBDFIT_SOUP_UNIT_COLOR_PLUS) uniform sampler2D colorPlus;
layout(binding = SUBDFIT_SOUP_UNIT_COLOR_MINUS) uniform sampler2D colorMinus;
layout(binding = SUBDFIT_SOUP_UNIT_TRIANGLE_PLUS) uniform isampler2D trianglePlus;
layout(binding = SUBDFIT_SOUP_UNIT_TRIANGLE_MINUS) uniform isampler2D triangleMinus;
layout(binding = SUBDFIT_SOUP_UNIT_TARGET) uniform sampler2D target;

SUBDFIT_DECLARE_ACCUMULATOR(TriangleDelta, SUBDFIT_SOUP_SSBO_TRIANGLE_DELTA, triangleDelta, addTriangleDelta)

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, textureSize(colorPlus, 0)))) return;
    int tp = texelFetch(trianglePlus, pixel, 0).r;
    int tm = texelFetch(triangleMinus, pixel, 0).r;
    // Background in both renders: both are the clear colour, so Δ_p = 0 exactly.
    if (tp < 0 && tm < 0) return;
    vec3 t = texelFetch(target, pixel, 0).rgb;
    vec3 ePlus = texelFetch(colorPlus, pixel, 0).rgb - t;
    vec3 eMinus = texelFetch(colorMinus, pixel, 0).rgb - t;
    float delta = dot(ePlus, ePlus) - dot(eMinus, eMinus);
    if (delta == 0.0) return;
#ifdef SUBDFIT_SOUP_FULL_IMAGE
    addTriangleDelta(gl_LocalInvocationIndex, delta);
#else
    if (tp >= 0) addTriangleDelta(uint(tp), delta);
    if (tm >= 0 && tm != tp) addTriangleDelta(uint(tm), delta);
#endif
}
