// The reference (a plain triangle mesh) with exactly the shading of the cage's limit surface,
// and, in a scene with materials, its glTF metallic-roughness material: factors always, each
// texture only in the variant whose define names it.
#include "bindings.h"
#include "shading.glsl"

in vec3 vWorldPosition;
in vec3 vWorldNormal;

layout(location = SUBDFIT_ATTACHMENT_COLOR) out vec4 outColor;
layout(location = SUBDFIT_ATTACHMENT_FACE_ID) out int outFaceId;
layout(location = SUBDFIT_ATTACHMENT_PATCH_UV) out vec2 outPatchUv;

uniform mat4 uView;
uniform vec3 uEye;

#ifdef SUBDFIT_MATERIAL
in vec2 vUv;
in vec4 vColor;

uniform vec4 uBaseColorFactor;
uniform float uMetallicFactor, uRoughnessFactor, uNormalScale, uOcclusionStrength, uAlphaCutoff;
uniform vec3 uEmissiveFactor;

// Each texture with its KHR_texture_transform (identity without one). Base colour and emissive
// textures are sRGB textures: fetches return linear values.
#define SUBDFIT_TEXTURE(NAME, UNIT) \
    layout(binding = UNIT) uniform sampler2D NAME##Texture; \
    uniform mat3 u##NAME##Transform; \
    vec4 NAME##Sample() { return texture(NAME##Texture, (u##NAME##Transform * vec3(vUv, 1.0)).xy); }
#ifdef SUBDFIT_BASE_COLOR_TEXTURE
SUBDFIT_TEXTURE(baseColor, SUBDFIT_UNIT_BASE_COLOR)
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_TEXTURE
SUBDFIT_TEXTURE(metallicRoughness, SUBDFIT_UNIT_METALLIC_ROUGHNESS)
#endif
#ifdef SUBDFIT_NORMAL_TEXTURE
SUBDFIT_TEXTURE(normal, SUBDFIT_UNIT_NORMAL)
#endif
#ifdef SUBDFIT_OCCLUSION_TEXTURE
SUBDFIT_TEXTURE(occlusion, SUBDFIT_UNIT_OCCLUSION)
#endif
#ifdef SUBDFIT_EMISSIVE_TEXTURE
SUBDFIT_TEXTURE(emissive, SUBDFIT_UNIT_EMISSIVE)
#endif

#ifdef SUBDFIT_NORMAL_TEXTURE
// No TANGENT attribute is read: the tangent frame comes from the screen-space derivatives of
// position and texture coordinates (a cotangent frame), T along +u and B along +v. glTF's v
// grows downwards through the image while a normal map's green points up it, hence −y.
vec3 mappedNormal(vec3 N) {
    vec3 dp1 = dFdx(vWorldPosition), dp2 = dFdy(vWorldPosition);
    vec2 duv1 = dFdx(vUv), duv2 = dFdy(vUv);
    vec3 dp2perp = cross(dp2, N), dp1perp = cross(N, dp1);
    vec3 T = dp2perp * duv1.x + dp1perp * duv2.x;
    vec3 B = dp2perp * duv1.y + dp1perp * duv2.y;
    float scale = max(dot(T, T), dot(B, B));
    if (!(scale > 0.0)) return N;
    vec3 t = normalSample().xyz * 2.0 - 1.0;
    t.xy *= uNormalScale;
    return normalize(inversesqrt(scale) * (t.x * T - t.y * B) + t.z * N);
}
#endif

SurfacePoint surfacePoint() {
    vec4 base = uBaseColorFactor * vColor;
#ifdef SUBDFIT_BASE_COLOR_TEXTURE
    base *= baseColorSample();
#endif
    if (base.a < uAlphaCutoff) discard;  // alphaMode MASK (the cut-off is 0 otherwise)
    SurfacePoint s;
    s.baseColor = base.rgb;
    s.metallic = uMetallicFactor;
    s.roughness = uRoughnessFactor;
#ifdef SUBDFIT_METALLIC_ROUGHNESS_TEXTURE
    vec4 mr = metallicRoughnessSample();
    s.roughness *= mr.g;
    s.metallic *= mr.b;
#endif
    s.occlusion = 1.0;
#ifdef SUBDFIT_OCCLUSION_TEXTURE
    s.occlusion = 1.0 + uOcclusionStrength * (occlusionSample().r - 1.0);
#endif
    s.emissive = uEmissiveFactor;
#ifdef SUBDFIT_EMISSIVE_TEXTURE
    s.emissive *= emissiveSample().rgb;
#endif
    return s;
}
#endif

void main() {
    vec3 n = dot(vWorldNormal, vWorldNormal) > 0.0 ? normalize(vWorldNormal) : vec3(0.0, 0.0, 1.0);
    if (dot(n, uEye - vWorldPosition) < 0.0) n = -n;
#ifdef SUBDFIT_MATERIAL
    SurfacePoint s = surfacePoint();
#ifdef SUBDFIT_NORMAL_TEXTURE
    n = mappedNormal(n);
#endif
    vec3 v = normalize(uEye - vWorldPosition);
    outColor = vec4(shadeMaterial(normalize(mat3(uView) * n), normalize(mat3(uView) * v), s), 1.0);
#else
    outColor = vec4(shadeLambert(normalize(mat3(uView) * n)), 1.0);
#endif
    outFaceId = gl_PrimitiveID;
    outPatchUv = vec2(0.0);
}
