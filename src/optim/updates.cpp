#include "optim/updates.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bindings.h"
#include "gl/dispatch.h"
#include "gl/texture.h"
#include "util/error.h"

namespace subdfit::optim {
namespace {

using gl::groupsOf;

const gl::ProgramSpec kPerturb{"perturb", {{GL_COMPUTE_SHADER, "perturb.comp"}}};
const gl::ProgramSpec kResolve{"resolve_gradient", {{GL_COMPUTE_SHADER, "resolve_gradient.comp"}}};
const gl::ProgramSpec kPrecondition{"precondition", {{GL_COMPUTE_SHADER, "precondition.comp"}}};
const gl::ProgramSpec kSharedMoment{"shared_moment", {{GL_COMPUTE_SHADER, "shared_moment.comp"}}};
const gl::ProgramSpec kAdam{
    "adam", {{GL_COMPUTE_SHADER, "adam.comp"}}, {"SUBDFIT_ADAM_SHARED_MOMENT", "SUBDFIT_ADAM_NOISE_GATE"}};
const gl::ProgramSpec kVertexUpdate{
    "vertex_update",
    {{GL_COMPUTE_SHADER, "vertex_update.comp"}},
    {"SUBDFIT_ADAM_SHARED_MOMENT", "SUBDFIT_ADAM_NOISE_GATE", "SUBDFIT_PROJECT_TANGENTIAL"}};
// The most floats a group may hold for all its Jacobi sweeps (and a vertex group's whole update)
// to run in one work group: two iterates in the 32 KB of shared memory that GL 4.3 guarantees.
constexpr int kOneGroupFloats = 4096;
constexpr gl::VariantBits kAdamSharedMoment = 1u << 0, kAdamNoiseGate = 1u << 1, kProjectTangential = 1u << 2;

// The share of white noise's variance that Adam's bias-corrected first moment keeps after t
// steps: Var(m̂) / σ² = (1 − β)(1 + β^t) / ((1 + β)(1 − β^t)); 1 at the first step.
float noiseShare(float beta1, int steps) {
    const double b = beta1, bt = std::pow(b, steps);
    return float((1.0 - b) * (1.0 + bt) / ((1.0 + b) * (1.0 - bt)));
}

gl::VariantBits adamBits(const GroupSettings& s) {
    return (s.sharedMoment ? kAdamSharedMoment : 0) | (s.noiseGate > 0.0f ? kAdamNoiseGate : 0);
}

// Counts the step and sets Adam's uniforms (glsl/adam.glsl) on `program`, in use, and binds the
// moments.
void beginAdamStep(const gl::Program& program, ParameterGroup& group, float learningRate) {
    const auto& s = group.settings();
    ++group.adamSteps;
    group.changed();
    program.set("uLearningRate", learningRate);
    program.set("uBeta1", s.beta1);
    program.set("uBeta2", s.beta2);
    program.set("uBiasCorrection1", 1.0f - std::pow(s.beta1, float(group.adamSteps)));
    program.set("uBiasCorrection2", 1.0f - std::pow(s.beta2, float(group.adamSteps)));
    program.set("uAdamEpsilon", 1e-12f);
    if (s.noiseGate > 0.0f) {
        program.set("uNoiseShare", noiseShare(s.beta1, group.adamSteps));
        program.set("uGateStrength", s.noiseGate);
    }
    group.moment1.bindStorage(SUBDFIT_SSBO_MOMENT1);
    group.moment2.bindStorage(SUBDFIT_SSBO_MOMENT2);
    if (s.sharedMoment) group.groupMoment2.bindStorage(SUBDFIT_SSBO_GROUP_MOMENT2);
}

}  // namespace

void perturb(gl::ProgramCache& programs, ParameterGroup& group, std::uint32_t counter, std::uint32_t seed) {
    const auto& program = programs.get(kPerturb);
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

void resolveGradient(gl::ProgramCache& programs, ParameterGroup& group) {
    const auto& program = programs.get(kResolve);
    program.use();
    program.set("uCount", unsigned(group.count()));
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    group.gradient.bindStorage(SUBDFIT_SSBO_GRADIENT);
    glDispatchCompute(groupsOf(group.count(), 256), 1, 1);
    // Read next as storage (Adam), as a texture (the preconditioner) or back by the host.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

void precondition(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency, float lambda,
                  int iterations, gl::Buffer& scratch) {
    if (iterations <= 0 || lambda <= 0.0f) {
        group.gradientSmooth.copyFrom(group.gradient);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        return;
    }
    const bool oneGroup = group.count() <= kOneGroupFloats;
    const int channels = group.count() / adjacency.vertexCount;
    gl::Defines defines{{"SUBDFIT_CHANNELS", std::to_string(channels)}};
    if (oneGroup) defines["SUBDFIT_PRECONDITION_ONE_GROUP"] = std::to_string(kOneGroupFloats);
    const auto& program = programs.get(kPrecondition, 0, defines);
    program.use();
    program.set("uVertexCount", adjacency.vertexCount);
    program.set("uLambda", lambda);
    const gl::BufferTexture gradient = gl::BufferTexture::ofFloats(group.gradient, channels);
    gradient.bind(SUBDFIT_UNIT_JACOBI_GRADIENT);
    adjacency.offsetsView.bind(SUBDFIT_UNIT_ADJACENCY_OFFSETS);
    adjacency.indicesView.bind(SUBDFIT_UNIT_ADJACENCY_INDICES);
    if (oneGroup) {
        program.set("uIterations", iterations);
        group.gradientSmooth.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        return;
    }
    // Jacobi ping-pong; the sweep count is arranged so the last one writes gradientSmooth.
    const gl::BufferTexture scratchView = gl::BufferTexture::ofFloats(scratch, channels);
    const gl::BufferTexture smoothView = gl::BufferTexture::ofFloats(group.gradientSmooth, channels);
    const gl::BufferTexture* in = &gradient;
    for (int k = 0; k < iterations; ++k) {
        const bool last = (iterations - 1 - k) % 2 == 0;
        in->bind(SUBDFIT_UNIT_JACOBI_IN);
        (last ? group.gradientSmooth : scratch).bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
        glDispatchCompute(groupsOf(adjacency.vertexCount, 128), 1, 1);
        // The next sweep fetches what this one stored.
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        in = last ? &smoothView : &scratchView;
    }
}

void adamStep(gl::ProgramCache& programs, ParameterGroup& group, const gl::Buffer& gradient, float learningRate) {
    const auto& s = group.settings();
    if (s.sharedMoment) {
        const auto& reduce = programs.get(kSharedMoment);
        reduce.use();
        reduce.set("uCount", unsigned(group.count()));
        reduce.set("uBeta2", s.beta2);
        gradient.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
        group.groupMoment2.bindStorage(SUBDFIT_SSBO_GROUP_MOMENT2);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    const auto& program = programs.get(kAdam, adamBits(s));
    program.use();
    program.set("uCount", unsigned(group.count()));
    beginAdamStep(program, group, learningRate);
    group.theta.bindStorage(SUBDFIT_SSBO_THETA);
    gradient.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
    glDispatchCompute(groupsOf(group.count(), 256), 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

bool updatesInOneGroup(const ParameterGroup& group) { return group.count() <= kOneGroupFloats; }

void updateVertices(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency, float lambda,
                    int iterations, const TangentialProjection* projection, float learningRate) {
    SUBDFIT_CHECK(updatesInOneGroup(group) && group.count() == 3 * adjacency.vertexCount);
    const auto& program =
        programs.get(kVertexUpdate, adamBits(group.settings()) | (projection ? kProjectTangential : 0),
                     {{"SUBDFIT_CHANNELS", "3"}, {"SUBDFIT_PRECONDITION_ONE_GROUP", std::to_string(kOneGroupFloats)}});
    program.use();
    program.set("uVertexCount", adjacency.vertexCount);
    program.set("uLambda", lambda);
    // No sweep at λ = 0: they would round g, where precondition() copies it.
    program.set("uIterations", lambda > 0.0f ? std::max(iterations, 0) : 0);
    adjacency.offsetsView.bind(SUBDFIT_UNIT_ADJACENCY_OFFSETS);
    adjacency.indicesView.bind(SUBDFIT_UNIT_ADJACENCY_INDICES);
    if (projection) {
        program.set("uKeep", projection->keep);
        projection->bind();
    }
    beginAdamStep(program, group, learningRate);
    group.theta.bindStorage(SUBDFIT_SSBO_THETA);
    group.gradientSum.bindStorage(SUBDFIT_SSBO_GRADIENT_SUM);
    group.gradient.bindStorage(SUBDFIT_SSBO_GRADIENT);
    group.gradientSmooth.bindStorage(SUBDFIT_SSBO_GRADIENT_SMOOTH);
    glDispatchCompute(1, 1, 1);
    // θ is read next by the stencils (storage) or by the host; g and the sums by the host.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace subdfit::optim
