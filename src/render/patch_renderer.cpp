#include "render/patch_renderer.h"

#include <algorithm>

#include "bindings.h"
#include "render/raster_pass.h"

namespace subdfit::render {
namespace {
constexpr int kPatchesPerDraw = 64;
}  // namespace

int crackFreeTessLevel(int requested, int maxPatchDepth) {
    int level = 1;
    while (level < std::max(requested, 1 << maxPatchDepth)) level *= 2;
    return std::min(level, 64);
}

PatchRenderer::PatchRenderer(const subdiv::PatchSet& patches, int tessLevel)
    : patchCount_(int(patches.patchInfo.size())),
      tessLevel_(crackFreeTessLevel(tessLevel, patches.maxPatchDepth)),
      patchInfo_(gl::Buffer::fromVector(patches.patchInfo)),
      patchCvs_(gl::Buffer::fromVector(patches.patchCvIndices)) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);  // core profile needs one bound, even with no attributes
    vertexArray_ = gl::GlHandle<gl::VertexArrayTraits>(id);
}

void PatchRenderer::draw(gl::ProgramCache& programs, const gl::Buffer& points, const Camera& camera,
                         const RenderTarget& target, const PatchMaps* maps) const {
    const bool withMaps = maps && (maps->displacement || maps->normalMap);
    gl::Defines defines;
    if (withMaps && maps->displacement) defines["SUBDFIT_DISPLACEMENT"] = "";
    if (withMaps && maps->normalMap) defines["SUBDFIT_NORMAL_MAP"] = "";
    const auto& program = programs.get("patch_raster",
                                       {{GL_VERTEX_SHADER, "patch.vert"},
                                        {GL_TESS_CONTROL_SHADER, "patch.tesc"},
                                        {GL_TESS_EVALUATION_SHADER, "patch.tese"},
                                        {GL_FRAGMENT_SHADER, "patch.frag"}},
                                       defines);
    beginRasterPass(program, camera, target);
    program.set("uTessLevel", float(tessLevel_));
    points.bindStorage(SUBDFIT_SSBO_POINTS);
    if (withMaps) {
        program.set("uMapResolution", maps->resolution);
        if (maps->bind) maps->bind();
    }
    patchInfo_.bindStorage(SUBDFIT_SSBO_PATCH_INFO);
    patchCvs_.bindStorage(SUBDFIT_SSBO_PATCH_CVS);
    glBindVertexArray(vertexArray_.id());
    glPatchParameteri(GL_PATCH_VERTICES, 1);
    // llvmpipe's draw module slows down superlinearly on one long patch draw; short draws of a
    // few hundred patches keep the cost linear in the patch count (measured by step-cost).
    for (int first = 0; first < patchCount_; first += kPatchesPerDraw)
        glDrawArrays(GL_PATCHES, first, std::min(kPatchesPerDraw, patchCount_ - first));
    glBindVertexArray(0);
}

}  // namespace subdfit::render
