#include "sge/passes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bindings.h"
#include "gl/dispatch.h"
#include "maps/map_parameters.h"
#include "optim/updates.h"
#include "util/error.h"

namespace subdfit::sge {
namespace {

using gl::groupsOf;

// One variant for the vertices' turns and one per texel group's channel count.
const gl::ProgramSpec kGradient{"gradient",
                                {{GL_COMPUTE_SHADER, "gradient.comp"}},
                                {"SUBDFIT_TEXELS", "SUBDFIT_FULL_IMAGE", "SUBDFIT_TEXELS_IN_ATLAS"}};
constexpr gl::VariantBits kGradientTexels = 1u << 0, kGradientFullImage = 1u << 1, kGradientInAtlas = 1u << 2;
const gl::ProgramSpec kScatterFaces{"scatter_faces", {{GL_COMPUTE_SHADER, "scatter_faces.comp"}}, {"SUBDFIT_FULL_IMAGE"}};
// Threads per vertex in scatter_faces.comp: a vertex has about a hundred sums, which one thread
// on a GPU walks as a long chain of dependent reads (docs/measurements.md).
constexpr int kScatterLanes = 16;

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
    : faceCount(int(faceOffsets.size()) - 1), vertexCount(vertexCount_) {
    std::vector<int> vertexFaces;
    const auto vertexFaceOffsets = transposeOffsets(faceOffsets, faceVertices, vertexCount, vertexFaces);
    // The pairs, in CSR by their first face: the faces after it that reach one of its vertices.
    std::vector<int> pairOffsetsOf{0}, pairFacesOf;
    std::vector<int> pairedWith(size_t(faceCount), -1);
    for (int a = 0; a < faceCount; ++a) {
        for (int k = faceOffsets[size_t(a)]; k < faceOffsets[size_t(a) + 1]; ++k) {
            const int v = faceVertices[size_t(k)];
            for (int j = vertexFaceOffsets[size_t(v)]; j < vertexFaceOffsets[size_t(v) + 1]; ++j) {
                const int b = vertexFaces[size_t(j)];
                if (b > a && pairedWith[size_t(b)] != a) {
                    pairedWith[size_t(b)] = a;
                    pairFacesOf.push_back(b);
                }
            }
        }
        std::sort(pairFacesOf.begin() + pairOffsetsOf.back(), pairFacesOf.end());
        pairOffsetsOf.push_back(int(pairFacesOf.size()));
    }
    // Each sum's vertices (a face's; a pair's union), transposed: vertex -> sums.
    std::vector<int> sumOffsets(faceOffsets), sumVertices(faceVertices);
    const auto verticesOf = [&](int f) {
        return std::pair{faceVertices.begin() + faceOffsets[size_t(f)], faceVertices.begin() + faceOffsets[size_t(f) + 1]};
    };
    for (int a = 0; a < faceCount; ++a)
        for (int k = pairOffsetsOf[size_t(a)]; k < pairOffsetsOf[size_t(a) + 1]; ++k) {
            const auto [aBegin, aEnd] = verticesOf(a);
            const auto [bBegin, bEnd] = verticesOf(pairFacesOf[size_t(k)]);
            std::set_union(aBegin, aEnd, bBegin, bEnd, std::back_inserter(sumVertices));
            sumOffsets.push_back(int(sumVertices.size()));
        }
    std::vector<int> vertexSumIndices;
    const auto vertexSumOffsets = transposeOffsets(sumOffsets, sumVertices, vertexCount, vertexSumIndices);
    pairOffsets = gl::Buffer::fromVector(pairOffsetsOf);
    pairFaces = gl::Buffer::fromVector(pairFacesOf);
    vertexOffsets = gl::Buffer::fromVector(vertexSumOffsets);
    vertexSums = gl::Buffer::fromVector(vertexSumIndices);
    faceDelta = gl::Buffer(GLsizeiptr(std::max<size_t>(1, sumOffsets.size() - 1)) * 2 * sizeof(std::uint32_t));
}

void accumulateGradient(gl::ProgramCache& programs, optim::ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& in, const gl::Buffer& loss) {
    const bool texels = group.kind() != optim::GroupKind::Vertices;
    SUBDFIT_CHECK(!texels || in.maps);
    SUBDFIT_CHECK(in.plus->faceInAlpha() && in.minus->faceInAlpha());
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
    if (!texels && !in.fullImage) program.set("uFaceCount", faces.faceCount);
    glBindTextureUnit(SUBDFIT_UNIT_COLOR_PLUS, in.plus->color().id());
    glBindTextureUnit(SUBDFIT_UNIT_COLOR_MINUS, in.minus->color().id());
    glBindTextureUnit(SUBDFIT_UNIT_TARGET, in.targetArray);
    faces.pairOffsets.bindStorage(SUBDFIT_SSBO_FACE_PAIR_OFFSETS);
    faces.pairFaces.bindStorage(SUBDFIT_SSBO_FACE_PAIRS);
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
    const auto& program =
        programs.get(kScatterFaces, fullImage ? 1u : 0u, {{"SUBDFIT_SCATTER_LANES", std::to_string(kScatterLanes)}});
    program.use();
    program.set("uVertexCount", faces.vertexCount);
    program.set("uCounter", counter);
    program.set("uSeed", seed);
    faces.faceDelta.bindStorage(SUBDFIT_SSBO_FACE_DELTA);
    faces.vertexOffsets.bindStorage(SUBDFIT_SSBO_VERTEX_SUM_OFFSETS);
    faces.vertexSums.bindStorage(SUBDFIT_SSBO_VERTEX_SUM_INDICES);
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    glDispatchCompute(groupsOf(faces.vertexCount, 128 / kScatterLanes), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    faces.faceDelta.clearToZero();
}

}  // namespace subdfit::sge
