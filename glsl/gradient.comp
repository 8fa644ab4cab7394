// G: one thread per pixel. Δ_p = f_p(θ+) − f_p(θ−) with f_p = ‖I_p − T_p‖², then for every
// parameter i of the perturbed group that produced the pixel in either render (the union of the
// base vertices reaching the + face and the − face; or, in a texel group's turn, of the nodes
// under the pixel's (u, v) in either render), g_i += Δ_p / (2 s_i ε). Where the two renders saw different faces
// (silhouettes, occlusion) both faces' vertices get the difference: that is what moves edges.
//
// s_i does not depend on the pixel, and the set only on the two faces, so Σ_p Δ_p s_i / 2ε =
// s_i Σ_p Δ_p / 2ε over the pixels of one pair of faces: each pixel adds into one sum (one
// atomic per pixel instead of one per contributing parameter), and scatter_sums.comp hands
// each sum to its vertices. A pixel both renders gave to face f (or one to f, the other to the
// background) adds into f's sum; one given to faces f and h that share a vertex, into their
// pair's sum (its vertices the union); to faces that share none, into both faces' sums.
#include "bindings.h"
#include "hash.glsl"
#include "atomics.glsl"
#include "fixed_point.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

// rgb: the shaded colour; a: the ptex face id, −1 on background (render/render_target.h).
layout(binding = SUBDFIT_IMAGE_COLOR_PLUS, rgba32f) readonly uniform image2D colorPlus;
layout(binding = SUBDFIT_IMAGE_COLOR_MINUS, rgba32f) readonly uniform image2D colorMinus;
layout(binding = SUBDFIT_IMAGE_TARGET, rgba32f) readonly uniform image2DArray targets;

// The pairs of faces that share a vertex, hashed by their second face (sge/face_pairs.h).
layout(binding = SUBDFIT_UNIT_PAIR_REGIONS) uniform isamplerBuffer pairRegions;
layout(binding = SUBDFIT_UNIT_PAIR_SLOTS) uniform isamplerBuffer pairSlots;
// Gradient terms in fixed point, so that a run repeats exactly; the loss is only reported.
SUBDFIT_DECLARE_FIXED_ACCUMULATOR(Gradient, SUBDFIT_SSBO_GRADIENT_SUM, gradient, addGradient)
SUBDFIT_DECLARE_FIXED_ACCUMULATOR(FaceDelta, SUBDFIT_SSBO_FACE_DELTA, faceDelta, addFaceDelta)
SUBDFIT_DECLARE_ACCUMULATOR(Loss, SUBDFIT_SSBO_LOSS, loss, addLoss)

#ifdef SUBDFIT_TEXELS
// A texel group's turn (SUBDFIT_TEXEL_CHANNELS floats per node, on the lattice whose face table
// starts at uTexelTable): its nodes under the pixel get the difference; no vertex does.
#ifdef SUBDFIT_TEXELS_IN_ATLAS
#define SUBDFIT_APPEARANCE_ATLAS
#endif
#include "maps.glsl"
layout(binding = SUBDFIT_IMAGE_UV_PLUS, rg32f) readonly uniform image2D uvPlus;
layout(binding = SUBDFIT_IMAGE_UV_MINUS, rg32f) readonly uniform image2D uvMinus;
uniform int uTexelResolution;
uniform int uTexelTable;
uniform uint uTexelSeed;

MapFootprint texelFootprint(int face, vec2 uv) {
#ifdef SUBDFIT_TEXELS_IN_ATLAS
    return atlasFootprint(face, uv, uTexelResolution, uTexelTable);
#else
    return footprint(face, uv, uTexelResolution, uTexelTable);
#endif
}
#endif

uniform int uTargetLayer;
uniform uint uCounter;
uniform uint uSeed;
uniform float uEpsilon;
#ifdef SUBDFIT_MEASURE_LOSS
uniform float uLossScale;  // 1 / (pixels × views), so the loss is a per-pixel mean
#endif
uniform int uFaceCount;    // ptex faces: the pairs' sums follow the faces'

// Where the search for face b starts among 2^bits slots (sge/face_pairs.h's pairSlotOf).
uint pairSlotOf(int b, int bits) { return (uint(b) * 2654435769u) >> uint(32 - bits); }

// The sum of faces a < b that share a vertex (the pairs' follow the faces'), or -1: a's slots
// probed from b's own to b or an empty one, which is never far (they are at most half full).
int pairSum(int a, int b) {
    ivec2 region = texelFetch(pairRegions, a).xy;  // (first slot, log2 of the slot count)
    uint mask = (1u << uint(region.y)) - 1u;
    for (uint slot = pairSlotOf(b, region.y), probe = 0u; probe <= mask; slot = (slot + 1u) & mask, ++probe) {
        ivec2 entry = texelFetch(pairSlots, region.x + int(slot)).xy;
        if (entry.x == b) return uFaceCount + entry.y;
        if (entry.x < 0) break;
    }
    return -1;
}

#ifdef SUBDFIT_TEXELS
// The nodes under the pixel's (face, u, v) in either render, each once.
void addTexelNode(int node, float scaledDelta) {
    for (uint c = 0u; c < uint(SUBDFIT_TEXEL_CHANNELS); ++c) {
        uint i = uint(SUBDFIT_TEXEL_CHANNELS) * uint(node) + c;
        addGradient(i, scaledDelta * perturbationSign(i, uCounter, uTexelSeed));
    }
}

void addTexelGradients(ivec2 pixel, int fp, int fm, float scaledDelta) {
    ivec4 plusNodes = ivec4(-1);
    if (fp >= 0) {
        plusNodes = texelFootprint(fp, imageLoad(uvPlus, pixel).rg).nodes;
        for (int k = 0; k < 4; ++k) {
            bool repeated = false;  // nodes are shared along cell and tile borders
            for (int j = 0; j < k; ++j) repeated = repeated || plusNodes[j] == plusNodes[k];
            if (!repeated) addTexelNode(plusNodes[k], scaledDelta);
        }
    }
    if (fm >= 0) {
        ivec4 minusNodes = texelFootprint(fm, imageLoad(uvMinus, pixel).rg).nodes;
        for (int k = 0; k < 4; ++k) {
            bool repeated = any(equal(plusNodes, ivec4(minusNodes[k])));
            for (int j = 0; j < k; ++j) repeated = repeated || minusNodes[j] == minusNodes[k];
            if (!repeated) addTexelNode(minusNodes[k], scaledDelta);
        }
    }
}
#endif

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, imageSize(colorPlus)))) return;
    vec4 plus = imageLoad(colorPlus, pixel);
    vec4 minus = imageLoad(colorMinus, pixel);
    int fp = int(plus.a);
    int fm = int(minus.a);
    // Background in both renders: both colours are the clear colour, so Δ = 0 exactly. Only the
    // loss, when it is being measured this step, still needs the target.
    bool covered = fp >= 0 || fm >= 0;
#ifndef SUBDFIT_MEASURE_LOSS
    if (!covered) return;
#endif

    vec3 target = imageLoad(targets, ivec3(pixel, uTargetLayer)).rgb;
    vec3 ePlus = plus.rgb - target;
    vec3 eMinus = minus.rgb - target;
    float fPlus = dot(ePlus, ePlus);
    float fMinus = dot(eMinus, eMinus);
    float delta = fPlus - fMinus;
    if (covered && delta != 0.0) {
        float scaledDelta = delta / (2.0 * uEpsilon);
#if defined(SUBDFIT_TEXELS)
        addTexelGradients(pixel, fp, fm, scaledDelta);
#elif defined(SUBDFIT_FULL_IMAGE)
        // The full-image estimator of plain SPSA, for comparison only: every pixel's Δ goes to
        // every parameter (scatter_vertices.comp reads this one sum for all vertices).
        addFaceDelta(0u, scaledDelta);
#else
        // The sums the pixel adds into: its face's (where one render saw background, the other's),
        // its pair's, or, for faces that share no vertex, both faces'. One call of the add in
        // the code: llvmpipe runs every branch for every pixel, masked.
        ivec2 sums = ivec2(fp >= 0 ? fp : fm, -1);
        if (fp != fm && fp >= 0 && fm >= 0) {
            int pair = pairSum(min(fp, fm), max(fp, fm));
            sums = pair >= 0 ? ivec2(pair, -1) : ivec2(fp, fm);
        }
        for (int k = 0; k < 2 && sums[k] >= 0; ++k) addFaceDelta(uint(sums[k]), scaledDelta);
#endif
    }
#ifdef SUBDFIT_MEASURE_LOSS
    // The loss goes to one of 256 slots by lane: a single float taking every pixel would
    // serialise, and a shared-memory reduction costs llvmpipe more in barriers than it saves.
    float pixelLoss = 0.5 * (fPlus + fMinus);
    if (pixelLoss != 0.0) addLoss(gl_LocalInvocationIndex, pixelLoss * uLossScale);
#endif
}
