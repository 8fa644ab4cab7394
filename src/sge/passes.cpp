#include "sge/passes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bindings.h"
#include "gl/dispatch.h"
#include "maps/map_parameters.h"
#include "optim/updates.h"
#include "sge/face_pairs.h"
#include "util/error.h"

namespace subdfit::sge {
namespace {

using gl::groupsOf;

// One variant for the vertices' turns and one per texel group's channel count; each with the
// loss measured or not (most steps do not, and llvmpipe would run its code masked at every pixel).
const gl::ProgramSpec kGradient{
    "gradient",
    {{GL_COMPUTE_SHADER, "gradient.comp"}},
    {"SUBDFIT_TEXELS", "SUBDFIT_FULL_IMAGE", "SUBDFIT_TEXELS_IN_ATLAS", "SUBDFIT_MEASURE_LOSS"}};
constexpr gl::VariantBits kGradientTexels = 1u << 0, kGradientFullImage = 1u << 1, kGradientInAtlas = 1u << 2,
                          kGradientLoss = 1u << 3;
const gl::ProgramSpec kScatterSums{"scatter_sums", {{GL_COMPUTE_SHADER, "scatter_sums.comp"}}};
const gl::ProgramSpec kScatterVertices{
    "scatter_vertices", {{GL_COMPUTE_SHADER, "scatter_vertices.comp"}}, {"SUBDFIT_FULL_IMAGE"}};

}  // namespace

FaceVertexTable::FaceVertexTable(const std::vector<int>& offsetsOf, const std::vector<int>& verticesOf,
                                 int vertexCount_)
    : faceCount(int(offsetsOf.size()) - 1), vertexCount(vertexCount_) {
    const FacePairs pairs = findFacePairs(offsetsOf, verticesOf, vertexCount);
    pairCount = int(pairs.first.size());
    faceOffsets = gl::Buffer::fromVector(offsetsOf);
    faceVertices = gl::Buffer::fromVector(verticesOf);
    std::vector<glm::ivec2> pairFacesOf(pairs.first.size());
    for (size_t k = 0; k < pairFacesOf.size(); ++k) pairFacesOf[k] = {pairs.first[k], pairs.second[k]};
    pairFaces = gl::Buffer::fromVector(pairFacesOf);
    pairRegions = gl::Buffer::fromVector(pairs.regions);
    pairSlots = gl::Buffer::fromVector(pairs.slots);
    faceOffsetsView = gl::BufferTexture(faceOffsets, GL_R32I);
    faceVerticesView = gl::BufferTexture(faceVertices, GL_R32I);
    pairFacesView = gl::BufferTexture(pairFaces, GL_RG32I);
    pairRegionsView = gl::BufferTexture(pairRegions, GL_RG32I);
    pairSlotsView = gl::BufferTexture(pairSlots, GL_RG32I);
    faceDelta = gl::Buffer(GLsizeiptr(std::max(1, faceCount + pairCount)) * 2 * sizeof(std::uint32_t));
    vertexDelta = gl::Buffer(GLsizeiptr(std::max(1, vertexCount)) * 2 * sizeof(std::uint32_t));
}

void accumulateGradient(gl::ProgramCache& programs, optim::ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& in, const gl::Buffer& loss) {
    const bool texels = group.kind() != optim::GroupKind::Vertices;
    SUBDFIT_CHECK(!texels || in.maps);
    SUBDFIT_CHECK(in.plus->faceInAlpha() && in.minus->faceInAlpha());
    const gl::VariantBits lossBit = in.measureLoss ? kGradientLoss : 0;
    const auto& program =
        texels ? programs.get(
                     kGradient, kGradientTexels | (in.maps->inAtlas(group) ? kGradientInAtlas : 0) | lossBit,
                     {{"SUBDFIT_TEXEL_CHANNELS", std::to_string(group.count() / in.maps->layoutOf(group).nodeCount)}})
               : programs.get(kGradient, (in.fullImage ? kGradientFullImage : 0) | lossBit);
    program.use();
    program.set("uTargetLayer", in.targetLayer);
    program.set("uCounter", in.counter);
    program.set("uSeed", in.seed);
    program.set("uEpsilon", group.settings().epsilon);
    if (in.measureLoss) program.set("uLossScale", in.lossScale);
    if (!texels && !in.fullImage) program.set("uFaceCount", faces.faceCount);
    in.plus->color().bindImageForReading(SUBDFIT_IMAGE_COLOR_PLUS);
    in.minus->color().bindImageForReading(SUBDFIT_IMAGE_COLOR_MINUS);
    in.targets->bindImageForReading(SUBDFIT_IMAGE_TARGET);
    faces.pairRegionsView.bind(SUBDFIT_UNIT_PAIR_REGIONS);
    faces.pairSlotsView.bind(SUBDFIT_UNIT_PAIR_SLOTS);
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    loss.bindStorage(SUBDFIT_SSBO_LOSS);
    faces.faceDelta.bindStorage(SUBDFIT_SSBO_FACE_DELTA);
    if (texels) {
        program.set("uTexelResolution", in.maps->layoutOf(group).resolution);
        program.set("uTexelTable", in.maps->tableOffsetOf(group));
        program.set("uTexelSeed", in.seed ^ group.seedSalt());
        in.plus->patchUv().bindImageForReading(SUBDFIT_IMAGE_UV_PLUS);
        in.minus->patchUv().bindImageForReading(SUBDFIT_IMAGE_UV_MINUS);
        in.maps->bindFaceNodes();
    }
    // The renders wrote through the framebuffer, which later commands see without a barrier.
    glDispatchCompute(groupsOf(in.plus->width(), 16), groupsOf(in.plus->height(), 16), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void scatterFaceDeltas(gl::ProgramCache& programs, optim::ParameterGroup& group, FaceVertexTable& faces,
                       std::uint32_t counter, std::uint32_t seed, bool fullImage) {
    faces.faceDelta.bindStorage(SUBDFIT_SSBO_FACE_DELTA);
    faces.vertexDelta.bindStorage(SUBDFIT_SSBO_VERTEX_DELTA);
    if (!fullImage) {
        const auto& sums = programs.get(kScatterSums);
        sums.use();
        sums.set("uFaceCount", faces.faceCount);
        sums.set("uSumCount", faces.faceCount + faces.pairCount);
        faces.faceOffsetsView.bind(SUBDFIT_UNIT_FACE_VERTEX_OFFSETS);
        faces.faceVerticesView.bind(SUBDFIT_UNIT_FACE_VERTICES);
        faces.pairFacesView.bind(SUBDFIT_UNIT_PAIR_FACES);
        glDispatchCompute(groupsOf(faces.faceCount + faces.pairCount, 64), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    const auto& vertices = programs.get(kScatterVertices, fullImage ? 1u : 0u);
    vertices.use();
    vertices.set("uVertexCount", faces.vertexCount);
    vertices.set("uCounter", counter);
    vertices.set("uSeed", seed);
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    glDispatchCompute(groupsOf(faces.vertexCount, 64), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (fullImage) faces.faceDelta.clearToZero();  // scatter_sums.comp clears the sums it hands on
}

}  // namespace subdfit::sge
