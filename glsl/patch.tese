#include "bindings.h"
#include "osd_patch_basis"
#ifdef SUBDFIT_DISPLACEMENT
#include "maps.glsl"
#endif

layout(quads, equal_spacing, ccw) in;

flat in int tcPatch[];

out vec3 teWorldPosition;
out vec3 teWorldNormal;
out vec3 teTangentU;  // ∂P/∂u and ∂P/∂v of the ptex face: the normal map's tangent frame
out vec3 teTangentV;
flat out int tePtexFace;
out vec2 tePtexUv;

layout(std430, binding = SUBDFIT_SSBO_POINTS) readonly buffer Points { float points[]; };
layout(std430, binding = SUBDFIT_SSBO_PATCH_INFO) readonly buffer PatchInfo { ivec4 patchInfo[]; };
layout(std430, binding = SUBDFIT_SSBO_PATCH_CVS) readonly buffer PatchCvs { int patchCvs[]; };
#ifdef SUBDFIT_DISPLACEMENT
layout(std430, binding = SUBDFIT_SSBO_DISPLACEMENT) readonly buffer Displacement { float displacement[]; };
#endif

uniform mat4 uViewProjection;

#ifdef SUBDFIT_DISPLACEMENT
float heightAt(int face, vec2 uv) {
    MapFootprint m = mapFootprint(face, uv);
    return dot(m.weights, vec4(displacement[m.nodes.x], displacement[m.nodes.y], displacement[m.nodes.z],
                               displacement[m.nodes.w]));
}
#endif

vec3 point(int i) { return vec3(points[3 * i], points[3 * i + 1], points[3 * i + 2]); }

// P(s,t) = Σ_k w_k(s,t) CV_k with OpenSubdiv's basis (B-spline with boundary masks for regular
// patches, Gregory for the end caps around extraordinary vertices), plus ∂P/∂s and ∂P/∂t.
void evaluatePatch(ivec4 info, OsdPatchParam param, vec2 st, out vec3 P, out vec3 dPds, out vec3 dPdt) {
    float wP[20], wDs[20], wDt[20], wDss[20], wDst[20], wDtt[20];
    int count = OsdEvaluatePatchBasisNormalized(info.y, param, st.x, st.y,
                                                wP, wDs, wDt, wDss, wDst, wDtt);
    P = vec3(0.0);
    dPds = vec3(0.0);
    dPdt = vec3(0.0);
    for (int k = 0; k < count; ++k) {
        vec3 cv = point(patchCvs[info.x + k]);
        P += wP[k] * cv;
        dPds += wDs[k] * cv;
        dPdt += wDt[k] * cv;
    }
}

void main() {
    ivec4 info = patchInfo[tcPatch[0]];
    OsdPatchParam param = OsdPatchParamInit(info.z, info.w, 0.0);
    vec2 st = gl_TessCoord.xy;

    vec3 P, dPds, dPdt;
    evaluatePatch(info, param, st, P, dPds, dPdt);
    if (dot(cross(dPds, dPdt), cross(dPds, dPdt)) < 1e-24) {
        // The tangents vanish at some extraordinary corners: take them a hair inside.
        vec3 Q;
        evaluatePatch(info, param, mix(st, vec2(0.5), 1e-3), Q, dPds, dPdt);
    }
    // Patch-local derivatives -> ptex-face derivatives (a depth-d patch spans 1/2^d of the face).
    float fraction = OsdPatchParamGetParamFraction(param);
    vec3 dPdu = dPds / fraction, dPdv = dPdt / fraction;
    vec3 N = cross(dPdu, dPdv);
    vec3 unitN = dot(N, N) > 0.0 ? normalize(N) : vec3(0.0, 0.0, 1.0);

    float uv[2] = float[2](st.x, st.y);
    OsdPatchParamUnnormalize(param, uv);
    tePtexUv = vec2(uv[0], uv[1]);
    tePtexFace = OsdPatchParamGetFaceId(param);

#ifdef SUBDFIT_DISPLACEMENT
    // P' = P + d(u,v) N̂. Shading normal of the displaced surface to first order:
    // ∂P'/∂u ≈ ∂P/∂u + (∂d/∂u) N̂ (the d ∂N̂/∂u term is dropped: d is small against curvature).
    // ∂d/∂u by central differences half a map cell wide, one-sided at the tile's border, exactly
    // as the CPU twin (surface/displaced_surface.cpp): at a node that averages the slopes of the
    // cells on either side, so the shading does not break at every cell edge.
    float height = heightAt(tePtexFace, tePtexUv);
    float h = 0.5 / float(uMapResolution);
    float u0 = max(tePtexUv.x - h, 0.0), u1 = min(tePtexUv.x + h, 1.0);
    float v0 = max(tePtexUv.y - h, 0.0), v1 = min(tePtexUv.y + h, 1.0);
    float dddu = (heightAt(tePtexFace, vec2(u1, tePtexUv.y)) - heightAt(tePtexFace, vec2(u0, tePtexUv.y))) / (u1 - u0);
    float dddv = (heightAt(tePtexFace, vec2(tePtexUv.x, v1)) - heightAt(tePtexFace, vec2(tePtexUv.x, v0))) / (v1 - v0);
    P += height * unitN;
    dPdu += dddu * unitN;
    dPdv += dddv * unitN;
    N = cross(dPdu, dPdv);
    unitN = dot(N, N) > 0.0 ? normalize(N) : unitN;
#endif
    teWorldNormal = unitN;
    teTangentU = dPdu;
    teTangentV = dPdv;
    teWorldPosition = P;
    gl_Position = uViewProjection * vec4(P, 1.0);
}
