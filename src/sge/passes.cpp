#include "sge/passes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bindings.h"
#include "maps/map_parameters.h"
#include "optim/updates.h"
#include "util/error.h"

namespace subdfit::sge {
namespace {

GLuint groupsOf(int count, int size) { return GLuint((count + size - 1) / size); }

// One variant for the vertices' turns and one per texel group's channel count.
const gl::ProgramSpec kGradient{"gradient",
                                {{GL_COMPUTE_SHADER, "gradient.comp"}},
                                {"SUBDFIT_TEXELS", "SUBDFIT_FULL_IMAGE", "SUBDFIT_TEXELS_IN_ATLAS"}};
constexpr gl::VariantBits kGradientTexels = 1u << 0, kGradientFullImage = 1u << 1, kGradientInAtlas = 1u << 2;
const gl::ProgramSpec kScatterFaces{"scatter_faces", {{GL_COMPUTE_SHADER, "scatter_faces.comp"}}, {"SUBDFIT_FULL_IMAGE"}};

std::vector<int> transposeOffsets(const std::vector<int>& offsets, const std::vector<int>& indices, int columns,
                                  std::vector<int>& transposed) {
    std::vector<int> counts(size_t(columns) + 1, 0);
    for (int column : indices) ++counts[size_t(column) + 1];
    for (size_t c = 1; c < counts.size(); ++c) counts[c] += counts[c - 1];
    transposed.assign(indices.size(), 0);
    std::vector<int> fill(counts.begin(), counts.end() - 1);
    for (size_t row = 0; row + 1 < offsets.size(); ++row)
        for (int k = offsets[row]; k < offsets[row + 1]; ++k) transposed[size_t(fill[size_t(indices[k])]++)] = int(row);
    return counts;
}

}  // namespace

FaceVertexTable::FaceVertexTable(const std::vector<int>& faceOffsets, const std::vector<int>& faceVertices,
                                 int vertexCount_)
    : offsets(gl::Buffer::fromVector(faceOffsets)),
      indices(gl::Buffer::fromVector(faceVertices)),
      faceDelta(GLsizeiptr(std::max<size_t>(1, faceOffsets.size())) * 2 * sizeof(std::uint32_t)),
      vertexCount(vertexCount_) {
    std::vector<int> vertexFaceIndices;
    const auto vertexFaceOffsets = transposeOffsets(faceOffsets, faceVertices, vertexCount, vertexFaceIndices);
    vertexOffsets = gl::Buffer::fromVector(vertexFaceOffsets);
    vertexFaces = gl::Buffer::fromVector(vertexFaceIndices);
}

void accumulateGradient(gl::ProgramCache& programs, optim::ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& in, const gl::Buffer& loss) {
    const bool texels = group.kind() != optim::GroupKind::Vertices;
    SUBDFIT_CHECK(!texels || in.maps);
    const auto& program =
        texels ? programs.get(kGradient, kGradientTexels | (in.maps->inAtlas(group) ? kGradientInAtlas : 0),
                              {{"SUBDFIT_TEXEL_CHANNELS", std::to_string(group.count() / in.maps->layoutOf(group).nodeCount)}})
               : programs.get(kGradient, in.fullImage ? kGradientFullImage : 0);
    program.use();
    program.set("uTargetLayer", in.targetLayer);
    program.set("uCounter", in.counter);
    program.set("uSeed", in.seed);
    program.set("uEpsilon", group.settings().epsilon);
    program.set("uLossScale", in.lossScale);
    program.set("uMeasureLoss", in.measureLoss ? 1 : 0);
    glBindTextureUnit(SUBDFIT_UNIT_COLOR_PLUS, in.plus->color().id());
    glBindTextureUnit(SUBDFIT_UNIT_COLOR_MINUS, in.minus->color().id());
    glBindTextureUnit(SUBDFIT_UNIT_FACE_PLUS, in.plus->faceId().id());
    glBindTextureUnit(SUBDFIT_UNIT_FACE_MINUS, in.minus->faceId().id());
    glBindTextureUnit(SUBDFIT_UNIT_TARGET, in.targetArray);
    faces.offsets.bindStorage(SUBDFIT_SSBO_FACE_VERTEX_OFFSETS);
    faces.indices.bindStorage(SUBDFIT_SSBO_FACE_VERTEX_INDICES);
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    loss.bindStorage(SUBDFIT_SSBO_LOSS);
    faces.faceDelta.bindStorage(SUBDFIT_SSBO_FACE_DELTA);
    if (texels) {
        program.set("uTexelResolution", in.maps->layoutOf(group).resolution);
        program.set("uTexelTable", in.maps->tableOffsetOf(group));
        program.set("uTexelSeed", in.seed ^ group.seedSalt());
        glBindTextureUnit(SUBDFIT_UNIT_UV_PLUS, in.plus->patchUv().id());
        glBindTextureUnit(SUBDFIT_UNIT_UV_MINUS, in.minus->patchUv().id());
        in.maps->bindFaceNodes();
    }
    // The renders wrote through the framebuffer, which later commands see without a barrier.
    glDispatchCompute(groupsOf(in.plus->width(), 16), groupsOf(in.plus->height(), 16), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void scatterFaceDeltas(gl::ProgramCache& programs, optim::ParameterGroup& group, FaceVertexTable& faces,
                       std::uint32_t counter, std::uint32_t seed, bool fullImage) {
    const auto& program = programs.get(kScatterFaces, fullImage ? 1u : 0u);
    program.use();
    program.set("uVertexCount", faces.vertexCount);
    program.set("uCounter", counter);
    program.set("uSeed", seed);
    faces.faceDelta.bindStorage(SUBDFIT_SSBO_FACE_DELTA);
    faces.vertexOffsets.bindStorage(SUBDFIT_SSBO_VERTEX_FACE_OFFSETS);
    faces.vertexFaces.bindStorage(SUBDFIT_SSBO_VERTEX_FACE_INDICES);
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    glDispatchCompute(groupsOf(faces.vertexCount, 128), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    faces.faceDelta.clearToZero();
}

}  // namespace subdfit::sge
