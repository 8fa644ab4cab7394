// A point of a cage's limit surface, displaced by the heights where the scene has them: P(s,t),
// its shading normal, ∂P/∂u and ∂P/∂v (the normal map's tangent frame) and its ptex face and
// (u, v). glsl/tessellate.comp evaluates it at every vertex of the tessellation.
#include "surface_vertex.glsl"
#ifdef SUBDFIT_DISPLACEMENT
#include "displacement.glsl"
#endif

// The patches' points (render::StencilEvaluator), a point per texel: one gather each.
layout(binding = SUBDFIT_UNIT_PATCH_POINTS) uniform samplerBuffer points;
#ifdef SUBDFIT_SURFACE_PAIR
layout(binding = SUBDFIT_UNIT_PATCH_SECOND_POINTS) uniform samplerBuffer secondPoints;  // θ− beside θ+
#endif
// Per patch {cv offset, patch type, param0, param1}; its control points' indices four a texel
// (a patch's 16 or 20 start at a multiple of four): a fetch each instead of a load per int.
layout(binding = SUBDFIT_UNIT_PATCH_INFO) uniform isamplerBuffer patchInfo;
layout(binding = SUBDFIT_UNIT_PATCH_CVS) uniform isamplerBuffer patchCvs;


// OpenSubdiv's basis: B-spline with boundary masks for regular patches, Gregory for the end caps
// around extraordinary vertices. Each pass holds patches of one kind (render::PatchRenderer), so
// the basis is chosen here, at compile time: a SIMD rasterizer runs every branch of one chosen
// per patch.
#ifdef SUBDFIT_GREGORY_PATCHES
#define SUBDFIT_PATCH_CVS 20
#else
#define SUBDFIT_PATCH_CVS 16
#endif

// The weights of a patch's control points in P(s,t), ∂P/∂s and ∂P/∂t.
struct PatchBasis {
    float wP[SUBDFIT_PATCH_CVS], wDs[SUBDFIT_PATCH_CVS], wDt[SUBDFIT_PATCH_CVS];
};

PatchBasis patchBasis(OsdPatchParam param, vec2 st) {
    PatchBasis b;
    float wDss[SUBDFIT_PATCH_CVS], wDst[SUBDFIT_PATCH_CVS], wDtt[SUBDFIT_PATCH_CVS];
#ifdef SUBDFIT_GREGORY_PATCHES
    Osd_EvalBasisGregory(st.x, st.y, b.wP, b.wDs, b.wDt, wDss, wDst, wDtt);
#else
    Osd_EvalBasisBSpline(st.x, st.y, b.wP, b.wDs, b.wDt, wDss, wDst, wDtt);
    int boundary = OsdPatchParamGetBoundary(param);
    if (boundary != 0) Osd_boundBasisBSpline(boundary, b.wP, b.wDs, b.wDt, wDss, wDst, wDtt);
#endif
    return b;
}


// Σ_k w_k CV_k for the position; for the tangents, ∂/∂s and ∂/∂t per ptex-face unit (a depth-d
// patch spans 1/2^d of the face), and the unit normal between them.
SurfacePoint limitPoint(OsdPatchParam param, vec2 st, PatchBasis basis, vec3 cvs[SUBDFIT_PATCH_CVS]) {
    vec3 P = vec3(0.0), dPds = vec3(0.0), dPdt = vec3(0.0);
    for (int k = 0; k < SUBDFIT_PATCH_CVS; ++k) {
        P += basis.wP[k] * cvs[k];
        dPds += basis.wDs[k] * cvs[k];
        dPdt += basis.wDt[k] * cvs[k];
    }
    if (dot(cross(dPds, dPdt), cross(dPds, dPdt)) < 1e-24) {
        // The tangents vanish at some extraordinary corners: take them a hair inside.
        PatchBasis inside = patchBasis(param, mix(st, vec2(0.5), 1e-3));
        dPds = vec3(0.0);
        dPdt = vec3(0.0);
        for (int k = 0; k < SUBDFIT_PATCH_CVS; ++k) {
            dPds += inside.wDs[k] * cvs[k];
            dPdt += inside.wDt[k] * cvs[k];
        }
    }
    float fraction = OsdPatchParamGetParamFraction(param);
    SurfacePoint p;
    p.position = P;
    p.tangentU = dPds / fraction;
    p.tangentV = dPdt / fraction;
    vec3 N = cross(p.tangentU, p.tangentV);
    p.normal = dot(N, N) > 0.0 ? normalize(N) : vec3(0.0, 0.0, 1.0);
    float uv[2] = float[2](st.x, st.y);
    OsdPatchParamUnnormalize(param, uv);
    p.ptexUv = vec2(uv[0], uv[1]);
    p.ptexFace = OsdPatchParamGetFaceId(param);
    return p;
}

// A patch's control points of `pointSet`; `info` is its patchInfo texel.
void gatherCvs(ivec4 info, samplerBuffer pointSet, out vec3 cvs[SUBDFIT_PATCH_CVS]) {
    for (int k = 0; k < SUBDFIT_PATCH_CVS / 4; ++k) {
        ivec4 four = texelFetch(patchCvs, info.x / 4 + k);
        for (int c = 0; c < 4; ++c) cvs[4 * k + c] = texelFetch(pointSet, four[c]).xyz;
    }
}

// At (s, t) of patch `patchIndex` (render::PatchRenderer's patch order).
SurfacePoint surfacePoint(int patchIndex, vec2 st) {
    ivec4 info = texelFetch(patchInfo, patchIndex);
    OsdPatchParam param = OsdPatchParamInit(info.z, info.w, 0.0);
    vec3 cvs[SUBDFIT_PATCH_CVS];
    gatherCvs(info, points, cvs);
    SurfacePoint p = limitPoint(param, st, patchBasis(param, st), cvs);
#ifdef SUBDFIT_DISPLACEMENT
    displace(p, heightSample(p.ptexFace, p.ptexUv));
#endif
    return p;
}

#ifdef SUBDFIT_SURFACE_PAIR
// The same point of two surfaces, `points`' and `secondPoints`': one basis, one height.
void surfacePoints(int patchIndex, vec2 st, out SurfacePoint first, out SurfacePoint second) {
    ivec4 info = texelFetch(patchInfo, patchIndex);
    OsdPatchParam param = OsdPatchParamInit(info.z, info.w, 0.0);
    PatchBasis basis = patchBasis(param, st);
    vec3 cvs[SUBDFIT_PATCH_CVS];
    gatherCvs(info, points, cvs);
    first = limitPoint(param, st, basis, cvs);
    gatherCvs(info, secondPoints, cvs);
    second = limitPoint(param, st, basis, cvs);
#ifdef SUBDFIT_DISPLACEMENT
    HeightSample height = heightSample(first.ptexFace, first.ptexUv);
    displace(first, height);
    displace(second, height);
#endif
}
#endif
