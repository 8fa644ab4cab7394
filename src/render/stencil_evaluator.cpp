#include "render/stencil_evaluator.h"

#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "bindings.h"
#include "gl/dispatch.h"
#include "gl/texture.h"

namespace subdfit::render {

namespace {

// (source index, the weight's bits) per entry, as one RG32UI texel.
std::vector<std::uint32_t> interleavedEntries(const subdiv::PatchSet& patches) {
    std::vector<std::uint32_t> entries(2 * patches.stencilIndices.size());
    for (size_t k = 0; k < patches.stencilIndices.size(); ++k) {
        entries[2 * k] = std::uint32_t(patches.stencilIndices[k]);
        std::memcpy(&entries[2 * k + 1], &patches.stencilWeights[k], sizeof(float));
    }
    return entries;
}

const gl::ProgramSpec kStencilEval{"stencil_eval", {{GL_COMPUTE_SHADER, "stencil_eval.comp"}}, {"SUBDFIT_SECOND_SET"}};
constexpr gl::VariantBits kSecondSet = 1u << 0;

}  // namespace

StencilEvaluator::StencilEvaluator(const subdiv::PatchSet& patches)
    : baseCount_(patches.baseVertexCount),
      pointCount_(patches.pointCount),
      offsets_(gl::Buffer::fromVector(patches.stencilOffsets)),
      entries_(gl::Buffer::fromVector(interleavedEntries(patches))),
      entryTexture_(entries_, GL_RG32UI) {}

void StencilEvaluator::evaluate(gl::ProgramCache& programs, const gl::Buffer& controlPoints,
                                const gl::Buffer& points) const {
    dispatch(programs, controlPoints, points, nullptr, nullptr);
}

void StencilEvaluator::evaluate(gl::ProgramCache& programs, const gl::Buffer& controlPoints, const gl::Buffer& points,
                                const gl::Buffer& secondControlPoints, const gl::Buffer& secondPoints) const {
    dispatch(programs, controlPoints, points, &secondControlPoints, &secondPoints);
}

void StencilEvaluator::dispatch(gl::ProgramCache& programs, const gl::Buffer& controlPoints, const gl::Buffer& points,
                                const gl::Buffer* secondControlPoints, const gl::Buffer* secondPoints) const {
    const auto& program = programs.get(kStencilEval, secondPoints ? kSecondSet : 0);
    program.use();
    program.set("uBaseCount", baseCount_);
    program.set("uPointCount", pointCount_);
    const gl::BufferTexture source(controlPoints, GL_RGB32F);
    source.bind(SUBDFIT_UNIT_STENCIL_SOURCE);
    offsets_.bindStorage(SUBDFIT_SSBO_STENCIL_OFFSETS);
    entryTexture_.bind(SUBDFIT_UNIT_STENCIL_ENTRIES);
    points.bindStorage(SUBDFIT_SSBO_POINTS);
    std::optional<gl::BufferTexture> secondSource;
    if (secondPoints) {
        secondSource.emplace(*secondControlPoints, GL_RGB32F);
        secondSource->bind(SUBDFIT_UNIT_STENCIL_SECOND_SOURCE);
        secondPoints->bindStorage(SUBDFIT_SSBO_SECOND_POINTS);
    }
    glDispatchCompute(gl::groupsOf(pointCount_, 128), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

}  // namespace subdfit::render
