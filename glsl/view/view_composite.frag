// The viewer's composite pass: turns the raster buffers of the fit and of the reference into
// what one view mode shows. Buffers are fetched texel for texel (they have the viewport's size).
#include "bindings.h"
#include "hash.glsl"
#include "view_modes.h"
#if defined(SUBDFIT_DISPLACEMENT) || defined(SUBDFIT_NORMAL_MAP) || defined(SUBDFIT_BASE_COLOR_MAP) || defined(SUBDFIT_METALLIC_ROUGHNESS_MAP)
#include "maps.glsl"
#endif

layout(binding = 0) uniform sampler2D uFitColor;
layout(binding = 1) uniform isampler2D uFitFace;
layout(binding = 2) uniform sampler2D uFitUv;
layout(binding = 3) uniform sampler2D uTargetColor;

#ifdef SUBDFIT_DISPLACEMENT
layout(std430, binding = SUBDFIT_SSBO_DISPLACEMENT) readonly buffer Displacement { float displacement[]; };
#endif
#ifdef SUBDFIT_NORMAL_MAP
layout(binding = SUBDFIT_UNIT_MAP_NORMAL) uniform samplerBuffer normalMap;
#endif
#ifdef SUBDFIT_BASE_COLOR_MAP
layout(binding = SUBDFIT_UNIT_MAP_BASE_COLOR) uniform samplerBuffer baseColor;
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_MAP
layout(binding = SUBDFIT_UNIT_MAP_METALLIC_ROUGHNESS) uniform samplerBuffer metallicRoughness;
#endif

uniform int uMode;
uniform ivec2 uOrigin;     // the view's lower-left corner in the window
uniform float uScale;      // colour-map gain of the difference and map modes

out vec4 outColor;

vec3 background(float y) { return mix(vec3(0.10, 0.11, 0.13), vec3(0.22, 0.23, 0.26), y); }

// A perceptual dark-to-bright ramp (polynomial fit of matplotlib's inferno).
vec3 inferno(float t) {
    t = clamp(t, 0.0, 1.0);
    const vec3 c0 = vec3(0.000219, 0.001651, -0.019480);
    const vec3 c1 = vec3(0.106513, 0.563956, 3.932712);
    const vec3 c2 = vec3(11.602493, -3.972854, -15.942394);
    const vec3 c3 = vec3(-41.703996, 17.436398, 44.354145);
    const vec3 c4 = vec3(77.162935, -33.402359, -81.807311);
    const vec3 c5 = vec3(-71.319428, 32.626064, 73.209519);
    const vec3 c6 = vec3(25.131126, -12.242669, -23.070327);
    return clamp(c0 + t * (c1 + t * (c2 + t * (c3 + t * (c4 + t * (c5 + t * c6))))), 0.0, 1.0);
}

// Blue below zero, white at zero, red above: signed map values.
vec3 diverging(float s) {
    s = clamp(s, -1.0, 1.0);
    return s < 0.0 ? mix(vec3(1.0), vec3(0.15, 0.35, 0.85), -s) : mix(vec3(1.0), vec3(0.85, 0.2, 0.15), s);
}

float luminance(vec3 c) { return dot(c, vec3(0.299, 0.587, 0.114)); }

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy) - uOrigin;
    vec3 back = background(float(p.y) / float(textureSize(uFitColor, 0).y));
    vec4 fit = texelFetch(uFitColor, p, 0);
    int face = texelFetch(uFitFace, p, 0).r;
    vec2 uv = texelFetch(uFitUv, p, 0).rg;
    vec4 target = texelFetch(uTargetColor, p, 0);

    vec3 c = back;
    if (uMode == SUBDFIT_VIEW_FIT) {
        if (face >= 0) c = fit.rgb;
    } else if (uMode == SUBDFIT_VIEW_TARGET) {
        if (target.a > 0.0) c = target.rgb;
    } else if (uMode == SUBDFIT_VIEW_DIFFERENCE) {
        // The fit's per-pixel loss term: squared colour error, background counting as black.
        vec3 d = fit.rgb - target.rgb;
        if (face >= 0 || target.a > 0.0) c = inferno(sqrt(dot(d, d) / 3.0) * uScale);
    } else if (uMode == SUBDFIT_VIEW_FACE_ID) {
        if (face >= 0) {
            uint h = pcgHash(uint(face));
            c = vec3(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u)) / 255.0 * 0.8 + 0.2;
        }
    } else if (uMode == SUBDFIT_VIEW_UV) {
        if (face >= 0) c = vec3(uv, 0.3);
    }
#ifdef SUBDFIT_DISPLACEMENT
    else if (uMode == SUBDFIT_VIEW_DISPLACEMENT && face >= 0) {
        MapFootprint m = mapFootprint(face, uv);
        float h = 0.0;
        for (int k = 0; k < 4; ++k) h += m.weights[k] * displacement[m.nodes[k]];
        c = diverging(h * uScale) * (0.4 + 0.6 * clamp(2.0 * luminance(fit.rgb), 0.0, 1.0));  // shaded, for shape
    }
#endif
#ifdef SUBDFIT_NORMAL_MAP
    else if (uMode == SUBDFIT_VIEW_NORMAL_MAP && face >= 0) {
        MapFootprint m = mapFootprint(face, uv);
        vec2 t = vec2(0.0);
        for (int k = 0; k < 4; ++k) t += m.weights[k] * texelFetch(normalMap, m.nodes[k]).xy;
        c = vec3(0.5 + 0.5 * clamp(t * uScale, -1.0, 1.0), 1.0);  // the usual tangent-space colours
    }
#endif
#ifdef SUBDFIT_BASE_COLOR_MAP
    else if (uMode == SUBDFIT_VIEW_BASE_COLOR && face >= 0) {
        // The fitted texels as they are (sRGB), unlit: what baseColorTexture ships.
        MapFootprint m = appearanceFootprint(face, uv);
        vec3 t = vec3(0.0);
        for (int k = 0; k < 4; ++k)
            t += m.weights[k] * texelFetch(baseColor, m.nodes[k]).xyz;
        c = clamp(t, 0.0, 1.0);
    }
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_MAP
    else if (uMode == SUBDFIT_VIEW_METALLIC_ROUGHNESS && face >= 0) {
        // Roughness in green, metallic in blue: glTF's metallicRoughnessTexture packing.
        MapFootprint m = appearanceFootprint(face, uv);
        vec2 t = vec2(0.0);
        for (int k = 0; k < 4; ++k) t += m.weights[k] * texelFetch(metallicRoughness, m.nodes[k]).xy;
        c = vec3(0.0, clamp(t, 0.0, 1.0));
    }
#endif
    outColor = vec4(c, 1.0);
}
