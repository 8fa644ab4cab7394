// A point of a cage's limit surface, displaced by the heights where the scene has them: P(s,t),
// its shading normal, ∂P/∂u and ∂P/∂v (the normal map's tangent frame) and its ptex face and
// (u, v). glsl/tessellate.comp evaluates it at every vertex of the tessellation.
layout(std430, binding = SUBDFIT_SSBO_POINTS) readonly buffer Points { float points[]; };
layout(std430, binding = SUBDFIT_SSBO_PATCH_INFO) readonly buffer PatchInfo { ivec4 patchInfo[]; };
layout(std430, binding = SUBDFIT_SSBO_PATCH_CVS) readonly buffer PatchCvs { int patchCvs[]; };

#ifdef SUBDFIT_DISPLACEMENT
// The heights, one tile of (T + 3)² texels per ptex face: its nodes and the ring across its edges
// (glsl/height_tiles.comp), node (i, j) at texel (i + 1, j + 1) of the tile.
layout(binding = SUBDFIT_UNIT_HEIGHT_TILES) uniform sampler2D heightTiles;
uniform int uTilesPerRow;

// Bilinear, with at most one of u, v up to a cell outside [0, 1] (then in the cell between the
// tile's border and the ring across it).
float heightAt(int face, vec2 uv) {
    int n = uMapResolution;
    vec2 x = clamp(uv * float(n), vec2(-1.0), vec2(float(n + 1)));
    ivec2 cell = ivec2(x.x < 0.0 ? -1 : x.x >= float(n) ? n : min(int(x.x), n - 1),
                       x.y < 0.0 ? -1 : x.y >= float(n) ? n : min(int(x.y), n - 1));
    vec2 f = x - vec2(cell);
    ivec2 node = ivec2(face % uTilesPerRow, face / uTilesPerRow) * (n + 3) + 1 + cell;
    return mix(mix(texelFetch(heightTiles, node, 0).r, texelFetch(heightTiles, node + ivec2(1, 0), 0).r, f.x),
               mix(texelFetch(heightTiles, node + ivec2(0, 1), 0).r, texelFetch(heightTiles, node + ivec2(1, 1), 0).r, f.x),
               f.y);
}
#endif

vec3 point(int i) { return vec3(points[3 * i], points[3 * i + 1], points[3 * i + 2]); }

// P(s,t) = Σ_k w_k(s,t) CV_k with OpenSubdiv's basis (B-spline with boundary masks for regular
// patches, Gregory for the end caps around extraordinary vertices), plus ∂P/∂s and ∂P/∂t.
// Each draw holds patches of one kind (render::PatchRenderer), so the basis is chosen here, at
// compile time: a SIMD rasterizer runs every branch of a basis chosen per patch.
void evaluatePatch(ivec4 info, OsdPatchParam param, vec2 st, out vec3 P, out vec3 dPds, out vec3 dPdt) {
#ifdef SUBDFIT_GREGORY_PATCHES
    float wP[20], wDs[20], wDt[20], wDss[20], wDst[20], wDtt[20];
    int count = Osd_EvalBasisGregory(st.x, st.y, wP, wDs, wDt, wDss, wDst, wDtt);
#else
    float wP[16], wDs[16], wDt[16], wDss[16], wDst[16], wDtt[16];
    int count = Osd_EvalBasisBSpline(st.x, st.y, wP, wDs, wDt, wDss, wDst, wDtt);
    int boundary = OsdPatchParamGetBoundary(param);
    if (boundary != 0) Osd_boundBasisBSpline(boundary, wP, wDs, wDt, wDss, wDst, wDtt);
#endif
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

struct SurfacePoint {
    vec3 position, normal, tangentU, tangentV;
    int ptexFace;
    vec2 ptexUv;
};

// At (s, t) of patch `patchIndex` (render::PatchRenderer's patch order).
SurfacePoint surfacePoint(int patchIndex, vec2 st) {
    ivec4 info = patchInfo[patchIndex];
    OsdPatchParam param = OsdPatchParamInit(info.z, info.w, 0.0);
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
    SurfacePoint result;
    result.ptexUv = vec2(uv[0], uv[1]);
    result.ptexFace = OsdPatchParamGetFaceId(param);

#ifdef SUBDFIT_DISPLACEMENT
    vec2 at = clamp(result.ptexUv, 0.0, 1.0);
    P += heightAt(result.ptexFace, at) * unitN;
#ifndef SUBDFIT_LIMIT_SHADING  // (with it, the limit surface's normal shades: surface::ShadingNormal)
    // P' = P + d(u,v) N̂. Shading normal of the displaced surface to first order:
    // ∂P'/∂u ≈ ∂P/∂u + (∂d/∂u) N̂ (the d ∂N̂/∂u term is dropped: d is small against curvature).
    // ∂d/∂u by central differences half a map cell wide, reaching across the tile's border into
    // the neighbouring face's tile, exactly as the CPU twin (surface/displaced_surface.cpp): at a
    // node that averages the slopes of the cells on either side, so the shading breaks neither
    // at a cell edge nor at a face edge.
    float h = 0.5 / float(uMapResolution);
    float dddu = (heightAt(result.ptexFace, at + vec2(h, 0.0)) - heightAt(result.ptexFace, at - vec2(h, 0.0))) / (2.0 * h);
    float dddv = (heightAt(result.ptexFace, at + vec2(0.0, h)) - heightAt(result.ptexFace, at - vec2(0.0, h))) / (2.0 * h);
    dPdu += dddu * unitN;
    dPdv += dddv * unitN;
    N = cross(dPdu, dPdv);
    unitN = dot(N, N) > 0.0 ? normalize(N) : unitN;
#endif
#endif
    result.position = P;
    result.normal = unitN;
    result.tangentU = dPdu;
    result.tangentV = dPdv;
    return result;
}
