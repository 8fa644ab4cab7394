#include "sge/passes.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "bindings.h"
#include "maps/map_parameters.h"

namespace subdfit::sge {
namespace {

GLuint groupsOf(int count, int size) { return GLuint((count + size - 1) / size); }

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

void perturb(gl::ProgramCache& programs, ParameterGroup& group, std::uint32_t counter, std::uint32_t seed) {
    const auto& program = programs.get("perturb", {{GL_COMPUTE_SHADER, "perturb.comp"}});
    program.use();
    program.set("uCount", unsigned(group.count()));
    program.set("uCounter", counter);
    program.set("uSeed", seed ^ group.seedSalt());
    program.set("uEpsilon", group.settings().epsilon);
    group.theta.bindStorage(SUBDFIT_SSBO_THETA);
    group.thetaPlus.bindStorage(SUBDFIT_SSBO_THETA_PLUS);
    group.thetaMinus.bindStorage(SUBDFIT_SSBO_THETA_MINUS);
    glDispatchCompute(groupsOf(group.count(), 256), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void accumulateGradient(gl::ProgramCache& programs, ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& in, const gl::Buffer& loss) {
    gl::Defines effects = in.maps ? in.maps->defines() : gl::Defines{};
    if (in.fullImage) effects["SUBDFIT_FULL_IMAGE"] = "";
    const auto& program = programs.get("gradient", {{GL_COMPUTE_SHADER, "gradient.comp"}}, effects);
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
    if (in.maps) {
        program.set("uMapResolution", in.maps->layout().resolution);
        if (auto* g = in.maps->displacement()) program.set("uEpsilonDisplacement", g->settings().epsilon);
        if (auto* g = in.maps->normalMap()) program.set("uEpsilonNormalMap", g->settings().epsilon);
        glBindTextureUnit(SUBDFIT_UNIT_UV_PLUS, in.plus->patchUv().id());
        glBindTextureUnit(SUBDFIT_UNIT_UV_MINUS, in.minus->patchUv().id());
        in.maps->bindForGradient();
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    glDispatchCompute(groupsOf(in.plus->width(), 16), groupsOf(in.plus->height(), 16), 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void scatterFaceDeltas(gl::ProgramCache& programs, ParameterGroup& group, FaceVertexTable& faces,
                       std::uint32_t counter, std::uint32_t seed, bool fullImage) {
    const auto& program = programs.get("scatter_faces", {{GL_COMPUTE_SHADER, "scatter_faces.comp"}},
                                       fullImage ? gl::Defines{{"SUBDFIT_FULL_IMAGE", ""}} : gl::Defines{});
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

void resolveGradient(gl::ProgramCache& programs, ParameterGroup& group) {
    const auto& program = programs.get("resolve_gradient", {{GL_COMPUTE_SHADER, "resolve_gradient.comp"}});
    program.use();
    program.set("uCount", unsigned(group.count()));
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    group.gradient.bindStorage(SUBDFIT_SSBO_GRADIENT);
    glDispatchCompute(groupsOf(group.count(), 256), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void precondition(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency,
                  float lambda, int iterations, gl::Buffer& scratch) {
    if (iterations <= 0 || lambda <= 0.0f) {
        group.gradientSmooth.copyFrom(group.gradient);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        return;
    }
    const auto& program = programs.get("precondition", {{GL_COMPUTE_SHADER, "precondition.comp"}},
                                       {{"SUBDFIT_CHANNELS", std::to_string(group.count() / adjacency.vertexCount)}});
    program.use();
    program.set("uVertexCount", adjacency.vertexCount);
    program.set("uLambda", lambda);
    group.gradient.bindStorage(SUBDFIT_SSBO_GRADIENT);
    adjacency.offsets.bindStorage(SUBDFIT_SSBO_ADJACENCY_OFFSETS);
    adjacency.indices.bindStorage(SUBDFIT_SSBO_ADJACENCY_INDICES);
    // Jacobi ping-pong; the sweep count is arranged so the last one writes gradientSmooth.
    const gl::Buffer* in = &group.gradient;
    for (int k = 0; k < iterations; ++k) {
        const bool last = (iterations - 1 - k) % 2 == 0;
        gl::Buffer* out = last ? &group.gradientSmooth : &scratch;
        in->bindStorage(SUBDFIT_SSBO_SMOOTH_IN);
        out->bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
        glDispatchCompute(groupsOf(adjacency.vertexCount, 128), 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        in = out;
    }
}

void adamStep(gl::ProgramCache& programs, ParameterGroup& group, const gl::Buffer& gradient) {
    const auto& s = group.settings();
    ++group.adamSteps;
    gl::Defines defines;
    if (s.sharedMoment) {
        defines["SUBDFIT_ADAM_SHARED_MOMENT"] = "";
        const auto& reduce = programs.get("shared_moment", {{GL_COMPUTE_SHADER, "shared_moment.comp"}});
        reduce.use();
        reduce.set("uCount", unsigned(group.count()));
        reduce.set("uBeta2", s.beta2);
        gradient.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
        group.moment2.bindStorage(SUBDFIT_SSBO_MOMENT2);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    const auto& program = programs.get("adam", {{GL_COMPUTE_SHADER, "adam.comp"}}, defines);
    program.use();
    program.set("uCount", unsigned(group.count()));
    program.set("uLearningRate", s.learningRate);
    program.set("uBeta1", s.beta1);
    program.set("uBeta2", s.beta2);
    program.set("uBiasCorrection1", 1.0f - std::pow(s.beta1, float(group.adamSteps)));
    program.set("uBiasCorrection2", 1.0f - std::pow(s.beta2, float(group.adamSteps)));
    program.set("uAdamEpsilon", 1e-12f);
    group.theta.bindStorage(SUBDFIT_SSBO_THETA);
    gradient.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
    group.moment1.bindStorage(SUBDFIT_SSBO_MOMENT1);
    group.moment2.bindStorage(SUBDFIT_SSBO_MOMENT2);
    glDispatchCompute(groupsOf(group.count(), 256), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    group.gradient.clearToZero();
}

}  // namespace subdfit::sge
