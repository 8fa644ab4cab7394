#include "bindings.h"
#include "osd_patch_basis"

layout(quads, equal_spacing, ccw) in;

flat in int tcPatch[];

out vec3 teWorldPosition;
out vec3 teWorldNormal;
flat out int tePtexFace;
out vec2 tePtexUv;

layout(std430, binding = SUBDFIT_SSBO_POINTS) readonly buffer Points { float points[]; };
layout(std430, binding = SUBDFIT_SSBO_PATCH_INFO) readonly buffer PatchInfo { ivec4 patchInfo[]; };
layout(std430, binding = SUBDFIT_SSBO_PATCH_CVS) readonly buffer PatchCvs { int patchCvs[]; };

uniform mat4 uViewProjection;

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
    vec3 N = cross(dPds, dPdt);
    if (dot(N, N) < 1e-24) {
        // The tangents vanish at some extraordinary corners: take the normal a hair inside.
        vec3 Q, dQds, dQdt;
        evaluatePatch(info, param, mix(st, vec2(0.5), 1e-3), Q, dQds, dQdt);
        N = cross(dQds, dQdt);
    }
    teWorldNormal = dot(N, N) > 0.0 ? normalize(N) : vec3(0.0, 0.0, 1.0);
    teWorldPosition = P;

    float uv[2] = float[2](st.x, st.y);
    OsdPatchParamUnnormalize(param, uv);
    tePtexUv = vec2(uv[0], uv[1]);
    tePtexFace = OsdPatchParamGetFaceId(param);
    gl_Position = uViewProjection * vec4(P, 1.0);
}
