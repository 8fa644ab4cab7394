#include "bindings.h"
#include "shading.glsl"
#if defined(SUBDFIT_NORMAL_MAP) || defined(SUBDFIT_BASE_COLOR_MAP) || defined(SUBDFIT_METALLIC_ROUGHNESS_MAP)
#include "maps.glsl"
#endif

in vec3 teWorldPosition;
in vec3 teWorldNormal;
in vec3 teTangentU;
in vec3 teTangentV;
flat in int tePtexFace;
in vec2 tePtexUv;

layout(location = SUBDFIT_ATTACHMENT_COLOR) out vec4 outColor;
layout(location = SUBDFIT_ATTACHMENT_FACE_ID) out int outFaceId;
layout(location = SUBDFIT_ATTACHMENT_PATCH_UV) out vec2 outPatchUv;

#ifdef SUBDFIT_NORMAL_MAP
layout(std430, binding = SUBDFIT_SSBO_NORMAL_MAP) readonly buffer NormalMap { float normalMap[]; };

// Tangent-space normal n_ts = normalize(x, y, 1) in the frame (T, B, N): T along ∂P/∂u made
// orthogonal to N, B = N × T (flipped to agree with ∂P/∂v) -- the frame the exported glTF's
// TANGENT attribute carries.
vec3 mappedNormal(vec3 N) {
    MapFootprint m = mapFootprint(tePtexFace, tePtexUv);
    vec2 t = vec2(0.0);
    for (int k = 0; k < 4; ++k) t += m.weights[k] * vec2(normalMap[2 * m.nodes[k]], normalMap[2 * m.nodes[k] + 1]);
    vec3 T = teTangentU - N * dot(N, teTangentU);
    if (dot(T, T) < 1e-20) return N;
    T = normalize(T);
    vec3 B = cross(N, T);
    if (dot(B, teTangentV) < 0.0) B = -B;
    return normalize(t.x * T + t.y * B + N);
}
#endif

#ifdef SUBDFIT_MATERIAL
#ifdef SUBDFIT_BASE_COLOR_MAP
layout(std430, binding = SUBDFIT_SSBO_BASE_COLOR) readonly buffer BaseColor { float baseColor[]; };
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_MAP
layout(std430, binding = SUBDFIT_SSBO_METALLIC_ROUGHNESS) readonly buffer MetallicRoughness { float metallicRoughness[]; };
#endif

// The fitted material: sRGB base colour and (roughness, metallic) bilinear between the nodes of
// the appearance lattice, clamped to what they mean; white, fully rough, not metallic without.
SurfacePoint surfacePoint() {
    SurfacePoint s = SurfacePoint(vec3(1.0), 0.0, 1.0, 1.0, vec3(0.0));
#if defined(SUBDFIT_BASE_COLOR_MAP) || defined(SUBDFIT_METALLIC_ROUGHNESS_MAP)
    MapFootprint m = appearanceFootprint(tePtexFace, tePtexUv);
#endif
#ifdef SUBDFIT_BASE_COLOR_MAP
    vec3 c = vec3(0.0);
    for (int k = 0; k < 4; ++k)
        c += m.weights[k] * vec3(baseColor[3 * m.nodes[k]], baseColor[3 * m.nodes[k] + 1], baseColor[3 * m.nodes[k] + 2]);
    s.baseColor = srgbToLinear(clamp(c, 0.0, 1.0));
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_MAP
    vec2 rm = vec2(0.0);
    for (int k = 0; k < 4; ++k)
        rm += m.weights[k] * vec2(metallicRoughness[2 * m.nodes[k]], metallicRoughness[2 * m.nodes[k] + 1]);
    rm = clamp(rm, 0.0, 1.0);
    s.roughness = rm.x;
    s.metallic = rm.y;
#endif
    return s;
}
#endif

uniform mat4 uView;
uniform vec3 uEye;

void main() {
    vec3 n = normalize(teWorldNormal);
#ifdef SUBDFIT_NORMAL_MAP
    n = mappedNormal(n);
#endif
    if (dot(n, uEye - teWorldPosition) < 0.0) n = -n;  // open surfaces are seen from both sides
#ifdef SUBDFIT_MATERIAL
    vec3 v = normalize(uEye - teWorldPosition);
    outColor = vec4(shadeMaterial(normalize(mat3(uView) * n), normalize(mat3(uView) * v), surfacePoint()), 1.0);
#else
    outColor = vec4(shadeLambert(normalize(mat3(uView) * n)), 1.0);
#endif
    outFaceId = tePtexFace;
    outPatchUv = tePtexUv;
}
