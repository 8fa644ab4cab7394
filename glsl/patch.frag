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
#ifndef SUBDFIT_FACE_IN_ALPHA  // else the face goes to the colour's alpha (render/render_target.h)
layout(location = SUBDFIT_ATTACHMENT_FACE_ID) out int outFaceId;
#endif
layout(location = SUBDFIT_ATTACHMENT_PATCH_UV) out vec2 outPatchUv;

#ifdef SUBDFIT_NORMAL_MAP
layout(binding = SUBDFIT_UNIT_MAP_NORMAL) uniform samplerBuffer normalMap;

// Tangent-space normal n_ts = normalize(x, y, 1) in the frame (T, B, N): T along ∂P/∂u made
// orthogonal to N, B = N × T (flipped to agree with ∂P/∂v) -- the frame the exported glTF's
// TANGENT attribute carries.
vec3 mappedNormal(vec3 N) {
    MapFootprint m = mapFootprint(tePtexFace, tePtexUv);
    vec2 t = vec2(0.0);
    for (int k = 0; k < 4; ++k) t += m.weights[k] * texelFetch(normalMap, m.nodes[k]).xy;
    vec3 T = teTangentU - N * dot(N, teTangentU);
    if (dot(T, T) < 1e-20) return N;
    T = normalize(T);
    vec3 B = cross(N, T);
    if (dot(B, teTangentV) < 0.0) B = -B;
    return normalize(t.x * T + t.y * B + N);
}
#endif

#ifdef SUBDFIT_ATLAS_NORMAL_TEXTURE
layout(binding = SUBDFIT_UNIT_CARRIED_ATLAS_NORMAL) uniform samplerBuffer atlasNormal;

// The atlas's normal texture in the frame its coordinates give, as glsl/mesh.frag derives it for
// the reference (a cotangent frame: T along +u, B along +v, the texture's green up the image),
// so both are shaded alike. mesh.frag takes it from screen-space derivatives; here the surface's
// own derivatives and the atlas coordinates' Jacobian give the same frame exactly: derivatives
// across a 2 × 2 pixel quad of tessellated triangles a pixel or two wide striped the shading
// (simplify/atlas_shading_normals.h bakes against this frame).
vec3 atlasMappedNormal(vec3 N) {
    mat2 duv = atlasUvJacobian(tePtexFace, tePtexUv);
    vec3 dp1 = teTangentU, dp2 = teTangentV;
    // T·dp1 = du1 and T·dp2 = du2 with T ⟂ N: the gradient of u, whichever way N faces.
    float det = dot(N, cross(dp1, dp2));
    if (!(abs(det) > 1e-6 * length(dp1) * length(dp2))) return N;
    vec3 dp2perp = cross(dp2, N) / det, dp1perp = cross(N, dp1) / det;
    vec3 T = dp2perp * duv[0].x + dp1perp * duv[1].x;
    vec3 B = dp2perp * duv[0].y + dp1perp * duv[1].y;
    float scale = max(dot(T, T), dot(B, B));
    if (!(scale > 0.0)) return N;
    MapFootprint m = appearanceFootprint(tePtexFace, tePtexUv);
    vec3 t = vec3(0.0);
    for (int k = 0; k < 4; ++k) t += m.weights[k] * texelFetch(atlasNormal, m.nodes[k]).xyz;
    t = t * 2.0 - 1.0;
    return normalize(inversesqrt(scale) * (t.x * T - t.y * B) + t.z * N);
}
#endif

#ifdef SUBDFIT_MATERIAL
#ifdef SUBDFIT_CARRIED_OCCLUSION
layout(binding = SUBDFIT_UNIT_CARRIED_OCCLUSION) uniform samplerBuffer carriedOcclusion;
#endif
#ifdef SUBDFIT_CARRIED_EMISSIVE
layout(binding = SUBDFIT_UNIT_CARRIED_EMISSIVE) uniform samplerBuffer carriedEmissive;
#endif
#ifdef SUBDFIT_BASE_COLOR_MAP
layout(binding = SUBDFIT_UNIT_MAP_BASE_COLOR) uniform samplerBuffer baseColor;
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_MAP
layout(binding = SUBDFIT_UNIT_MAP_METALLIC_ROUGHNESS) uniform samplerBuffer metallicRoughness;
#endif

// The fitted material: sRGB base colour and (roughness, metallic) bilinear between the nodes of
// the appearance lattice, clamped to what they mean; white, fully rough, not metallic without.
// The reference's occlusion and emission, where they are carried, on the same lattice.
SurfacePoint surfacePoint() {
    SurfacePoint s = SurfacePoint(vec3(1.0), 0.0, 1.0, 1.0, vec3(0.0));
#if defined(SUBDFIT_BASE_COLOR_MAP) || defined(SUBDFIT_METALLIC_ROUGHNESS_MAP) || defined(SUBDFIT_CARRIED_OCCLUSION) || defined(SUBDFIT_CARRIED_EMISSIVE)
    MapFootprint m = appearanceFootprint(tePtexFace, tePtexUv);
#endif
#ifdef SUBDFIT_BASE_COLOR_MAP
    vec3 c = vec3(0.0);
    for (int k = 0; k < 4; ++k) c += m.weights[k] * texelFetch(baseColor, m.nodes[k]).xyz;
    s.baseColor = srgbToLinear(clamp(c, 0.0, 1.0));
#endif
#ifdef SUBDFIT_METALLIC_ROUGHNESS_MAP
    vec2 rm = vec2(0.0);
    for (int k = 0; k < 4; ++k) rm += m.weights[k] * texelFetch(metallicRoughness, m.nodes[k]).xy;
    rm = clamp(rm, 0.0, 1.0);
    s.roughness = rm.x;
    s.metallic = rm.y;
#endif
#ifdef SUBDFIT_CARRIED_OCCLUSION
    s.occlusion = 0.0;
    for (int k = 0; k < 4; ++k) s.occlusion += m.weights[k] * texelFetch(carriedOcclusion, m.nodes[k]).x;
#endif
#ifdef SUBDFIT_CARRIED_EMISSIVE
    vec3 e = vec3(0.0);
    for (int k = 0; k < 4; ++k) e += m.weights[k] * texelFetch(carriedEmissive, m.nodes[k]).xyz;
    s.emissive = srgbToLinear(clamp(e, 0.0, 1.0));
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
#ifdef SUBDFIT_ATLAS_NORMAL_TEXTURE
    n = atlasMappedNormal(n);
#endif
#ifdef SUBDFIT_MATERIAL
    vec3 v = normalize(uEye - teWorldPosition);
    outColor = vec4(shadeMaterial(normalize(mat3(uView) * n), normalize(mat3(uView) * v), surfacePoint()), 1.0);
#else
    outColor = vec4(shadeLambert(normalize(mat3(uView) * n)), 1.0);
#endif
#ifdef SUBDFIT_FACE_IN_ALPHA
    outColor.a = float(tePtexFace);
#else
    outFaceId = tePtexFace;
#endif
    // A sliver at a silhouette can extrapolate its (u, v) past the face (a pixel centre inside
    // its snapped edges, outside its exact ones); every reader of the buffer clamps it so too.
    outPatchUv = clamp(tePtexUv, 0.0, 1.0);
}
