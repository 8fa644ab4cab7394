#include "render/patch_renderer.h"

#include <algorithm>

#include "bindings.h"
#include "render/raster_pass.h"

namespace subdfit::render {
namespace {

constexpr int kPatchesPerDraw = 64;

const gl::ProgramSpec kPatchRaster{"patch_raster",
                                   {{GL_VERTEX_SHADER, "patch.vert"},
                                    {GL_TESS_CONTROL_SHADER, "patch.tesc"},
                                    {GL_TESS_EVALUATION_SHADER, "patch.tese"},
                                    {GL_FRAGMENT_SHADER, "patch.frag"}},
                                   [] {
                                       std::vector<std::string> defines = kShadingDefines;  // bits 0-2
                                       defines.insert(defines.end(), {"SUBDFIT_DISPLACEMENT", "SUBDFIT_NORMAL_MAP",
                                                                      "SUBDFIT_BASE_COLOR_MAP",
                                                                      "SUBDFIT_METALLIC_ROUGHNESS_MAP",
                                                                      "SUBDFIT_APPEARANCE_ATLAS", "SUBDFIT_ATLAS_NORMAL_TEXTURE",
                                                                      "SUBDFIT_CARRIED_OCCLUSION", "SUBDFIT_CARRIED_EMISSIVE",
                                                                      "SUBDFIT_LIMIT_SHADING", "SUBDFIT_GREGORY_PATCHES",
                                                                      "SUBDFIT_FACE_IN_ALPHA"});
                                       return defines;
                                   }()};
constexpr gl::VariantBits kPatchDisplacement = 1u << 3, kPatchNormalMap = 1u << 4, kPatchBaseColor = 1u << 5,
                          kPatchMetallicRoughness = 1u << 6, kPatchAppearanceAtlas = 1u << 7,
                          kPatchAtlasNormal = 1u << 8, kPatchCarriedOcclusion = 1u << 9, kPatchCarriedEmissive = 1u << 10,
                          kPatchLimitShading = 1u << 11, kPatchGregory = 1u << 12,
                          kPatchFaceInAlpha = 1u << 13;

// Runs of consecutive patches of one kind (OpenSubdiv's patch arrays keep each kind together).
std::vector<PatchRun> patchRuns(const subdiv::PatchSet& patches) {
    std::vector<PatchRun> runs;
    for (int p = 0; p < int(patches.patchInfo.size()); ++p) {
        const bool gregory = patches.patchInfo[p].y == subdiv::kGregoryBasisPatch;
        if (runs.empty() || runs.back().gregory != gregory) runs.push_back({.first = p, .count = 0, .gregory = gregory});
        ++runs.back().count;
    }
    return runs;
}

}  // namespace

int crackFreeTessLevel(int requested, int maxPatchDepth) {
    int level = 1;
    while (level < std::max(requested, 1 << maxPatchDepth)) level *= 2;
    return std::min(level, 64);
}

PatchRenderer::PatchRenderer(const subdiv::PatchSet& patches, int tessLevel, ShadingModel shading)
    : patchCount_(int(patches.patchInfo.size())),
      tessLevel_(crackFreeTessLevel(tessLevel, patches.maxPatchDepth)),
      shading_(shading),
      runs_(patchRuns(patches)),
      patchInfo_(gl::Buffer::fromVector(patches.patchInfo)),
      patchCvs_(gl::Buffer::fromVector(patches.patchCvIndices)) {}

void PatchRenderer::draw(gl::ProgramCache& programs, const gl::Buffer& points, const Camera& camera,
                         const RenderTarget& target, const PatchMaps* maps) const {
    const gl::VariantBits mapBits =
        maps ? (maps->displacement ? kPatchDisplacement | (maps->limitShading ? kPatchLimitShading : 0) : 0) |
                   (maps->normalMap ? kPatchNormalMap : 0) |
                   (maps->baseColor ? kPatchBaseColor : 0) | (maps->metallicRoughness ? kPatchMetallicRoughness : 0) |
                   (maps->appearanceAtlas && (maps->baseColor || maps->metallicRoughness) ? kPatchAppearanceAtlas : 0)
             : 0;
    // The reference's textures the appearance lattice carries: only where it is drawn, with a
    // material (the normal texture only with its atlas, whose frame it is in).
    const bool carried = (mapBits & (kPatchBaseColor | kPatchMetallicRoughness)) && shading_ != ShadingModel::Geometry;
    const gl::VariantBits carriedBits =
        carried ? (maps->atlasNormal && (mapBits & kPatchAppearanceAtlas) ? kPatchAtlasNormal : 0) |
                      (maps->carriedOcclusion ? kPatchCarriedOcclusion : 0) | (maps->carriedEmissive ? kPatchCarriedEmissive : 0)
                : 0;
    const gl::VariantBits targetBits = target.faceInAlpha() ? kPatchFaceInAlpha : 0;
    beginRasterPass(target);  // each run of patches then uses its own program
    patchInfo_.bindStorage(SUBDFIT_SSBO_PATCH_INFO);
    patchCvs_.bindStorage(SUBDFIT_SSBO_PATCH_CVS);
    points.bindStorage(SUBDFIT_SSBO_POINTS);
    if (maps && maps->bind) maps->bind();
    vertexArray_.bind();
    glPatchParameteri(GL_PATCH_VERTICES, 1);
    for (const PatchRun& run : runs_) {
        const auto& program =
            programs.get(kPatchRaster, shadingBits(shading_) | mapBits | carriedBits | targetBits |
                                          (run.gregory ? kPatchGregory : 0));
        useWithCamera(program, camera);
        program.set("uTessLevel", float(tessLevel_));
        if (mapBits != 0) {
            program.set("uMapResolution", maps->resolution);
            program.set("uAppearanceResolution", maps->appearanceResolution);
            program.set("uAppearanceTable", maps->appearanceTable);
            if (maps->displacement) program.set("uMapHaloTable", maps->haloTable);
        }
        // llvmpipe's draw module slows down superlinearly on one long patch draw; short draws of
        // kPatchesPerDraw patches keep the cost linear in the patch count (measured by step-cost).
        for (int first = run.first; first < run.first + run.count; first += kPatchesPerDraw)
            glDrawArrays(GL_PATCHES, first, std::min(kPatchesPerDraw, run.first + run.count - first));
    }
    glBindVertexArray(0);
}

}  // namespace subdfit::render
