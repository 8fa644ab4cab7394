// Lambert under three coloured directional lights fixed to the camera, plus a little ambient.
// On the visible hemisphere the three cosines are independent, so a pixel's colour is close to
// an injective function of its normal: image differences see shape, not just silhouettes.
const vec3 SUBDFIT_LIGHT_DIRS[3] = vec3[3](normalize(vec3(0.6, 0.5, 1.0)),
                                           normalize(vec3(-0.8, 0.3, 0.6)),
                                           normalize(vec3(0.0, -0.9, 0.5)));
const vec3 SUBDFIT_LIGHT_COLORS[3] = vec3[3](vec3(0.85, 0.35, 0.25),
                                             vec3(0.25, 0.75, 0.35),
                                             vec3(0.25, 0.35, 0.85));
const vec3 SUBDFIT_AMBIENT = vec3(0.08);

// nView: unit normal in view space, already turned towards the camera.
vec3 shadeLambert(vec3 nView) {
    vec3 c = SUBDFIT_AMBIENT;
    for (int k = 0; k < 3; ++k) c += SUBDFIT_LIGHT_COLORS[k] * max(dot(nView, SUBDFIT_LIGHT_DIRS[k]), 0.0);
    return c;
}

#if defined(SUBDFIT_SHADING_UNLIT) || defined(SUBDFIT_SHADING_LAMBERT) || defined(SUBDFIT_SHADING_PBR)
#define SUBDFIT_MATERIAL
// Scenes with materials: the same three directions with near-white lights (a warm key, a cool
// fill, a dim light from below) and a grey ambient, so that the asset's own colours show. The
// image is compared, written and looked at in sRGB (shadeMaterial's result), where equal steps
// look about equally different.
const vec3 SUBDFIT_MATERIAL_LIGHTS[3] = vec3[3](vec3(0.78, 0.74, 0.68),
                                                vec3(0.28, 0.31, 0.36),
                                                vec3(0.14, 0.14, 0.15));
// A white surface facing the camera reflects about 0.95: bright albedos stay below clipping,
// where their shading (the shape) would be lost.
const vec3 SUBDFIT_MATERIAL_AMBIENT = vec3(0.12);
const float SUBDFIT_PI = 3.14159265;

struct SurfacePoint {
    vec3 baseColor;  // linear
    float metallic, roughness, occlusion;
    vec3 emissive;   // linear
};

vec3 srgbToLinear(vec3 c) { return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c)); }
vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

// n, v: unit normal (towards the camera) and unit direction to the camera, in view space.
// glTF 2.0's BRDF (Appendix B): f = (1 − F) c_diff / π + F D V with c_diff = base (1 − metallic),
// F0 = mix(0.04, base, metallic), D and V the GGX distribution and height-correlated Smith
// visibility of α = roughness². A light of irradiance E contributes π f E (n·l), so a white
// Lambert surface facing a light reflects E.
vec3 shadeMaterial(vec3 n, vec3 v, SurfacePoint s) {
#ifdef SUBDFIT_SHADING_UNLIT
    return linearToSrgb(s.baseColor);
#else
#ifdef SUBDFIT_SHADING_PBR
    vec3 diffuse = s.baseColor * (1.0 - s.metallic);
    vec3 f0 = mix(vec3(0.04), s.baseColor, s.metallic);
    float a = max(s.roughness * s.roughness, 2e-3);
    float a2 = a * a;
    float nv = max(dot(n, v), 1e-4);
    // The ambient light reaches the diffuse part and, about uniformly, the specular one.
    vec3 c = SUBDFIT_MATERIAL_AMBIENT * s.occlusion * (diffuse + f0);
    for (int k = 0; k < 3; ++k) {
        vec3 l = SUBDFIT_LIGHT_DIRS[k];
        float nl = dot(n, l);
        if (nl <= 0.0) continue;
        vec3 h = normalize(l + v);
        float nh = max(dot(n, h), 0.0);
        vec3 F = f0 + (1.0 - f0) * pow(1.0 - max(dot(v, h), 0.0), 5.0);
        float denominator = nh * nh * (a2 - 1.0) + 1.0;
        float D = a2 / (SUBDFIT_PI * denominator * denominator);
        float V = 0.5 / (nl * sqrt(nv * nv * (1.0 - a2) + a2) + nv * sqrt(nl * nl * (1.0 - a2) + a2));
        c += SUBDFIT_MATERIAL_LIGHTS[k] * nl * ((1.0 - F) * diffuse + SUBDFIT_PI * F * D * V);
    }
#else
    vec3 c = SUBDFIT_MATERIAL_AMBIENT * s.occlusion * s.baseColor;
    for (int k = 0; k < 3; ++k) c += SUBDFIT_MATERIAL_LIGHTS[k] * s.baseColor * max(dot(n, SUBDFIT_LIGHT_DIRS[k]), 0.0);
#endif
    return linearToSrgb(c + s.emissive);
#endif
}
#endif
