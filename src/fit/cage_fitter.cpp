#include "fit/cage_fitter.h"

#include <algorithm>
#include <cmath>

#include "mesh/mesh_adjacency.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

constexpr int kLossSlots = 256;  // see gradient.comp

std::vector<float> flatten(const std::vector<glm::vec3>& points) {
    std::vector<float> values;
    values.reserve(points.size() * 3);
    for (const auto& p : points) values.insert(values.end(), {p.x, p.y, p.z});
    return values;
}

sge::Adjacency uploadAdjacency(const mesh::PolygonMesh& cage) {
    const auto adjacency = mesh::vertexAdjacency(cage);
    return {gl::Buffer::fromVector(adjacency.offsets), gl::Buffer::fromVector(adjacency.neighbors),
            cage.vertexCount()};
}

}  // namespace

CageFitter::CageFitter(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const CageFitSettings& settings)
    : programs_(programs),
      settings_(settings),
      patches_(subdiv::buildPatchSet(cage)),
      stencils_(patches_),
      renderer_(patches_, settings.tessLevel),
      vertices_("vertices", flatten(cage.positions), settings.vertices),
      faceVertices_(patches_.faceVertexOffsets, patches_.faceVertexIndices, cage.vertexCount()),
      adjacency_(uploadAdjacency(cage)),
      pointsPlus_(stencils_.makePointBuffer()),
      pointsMinus_(stencils_.makePointBuffer()),
      smoothScratch_(vertices_.gradient.bytes()),
      loss_(sizeof(float) * kLossSlots),
      plus_(settings.resolution, settings.resolution),
      minus_(settings.resolution, settings.resolution) {}

void CageFitter::step(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss) {
    accumulate(targets, views, measureLoss);
    update();
}

void CageFitter::accumulate(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss) {
    // A distinct counter per sample keeps every sample's signs independent; the seed separates runs.
    const std::uint32_t counter = samples_++;
    sge::perturb(programs_, vertices_, counter, settings_.seed);
    stencils_.evaluate(programs_, vertices_.thetaPlus, pointsPlus_);
    stencils_.evaluate(programs_, vertices_.thetaMinus, pointsMinus_);
    const float pixels = float(settings_.resolution) * float(settings_.resolution);
    for (int view : views) {
        const auto& camera = targets.camera(view);
        renderer_.draw(programs_, pointsPlus_, camera, plus_);
        renderer_.draw(programs_, pointsMinus_, camera, minus_);
        sge::accumulateGradient(programs_, vertices_, faceVertices_,
                                {&plus_, &minus_, targets.colors().id(), view, counter, settings_.seed,
                                 1.0f / (pixels * float(views.size())), measureLoss},
                                loss_);
    }
    sge::scatterFaceDeltas(programs_, vertices_, faceVertices_, counter, settings_.seed);
    if (measureLoss) ++samplesSinceLoss_;
}

void CageFitter::update() {
    if (settings_.plannedSteps > 0) {
        // Exponential annealing to a tenth: large moves first, then settle within the noise.
        const float progress = std::min(1.0f, float(steps_) / float(settings_.plannedSteps));
        vertices_.settings().learningRate = settings_.vertices.learningRate * std::pow(0.1f, progress);
    }
    sge::precondition(programs_, vertices_, adjacency_, settings_.smoothingLambda,
                      settings_.smoothingIterations, smoothScratch_);
    sge::adamStep(programs_, vertices_);
    ++steps_;
}

std::vector<float> CageFitter::takeGradient() {
    auto gradient = vertices_.gradient.read<float>();
    vertices_.gradient.clearToZero();
    return gradient;
}

float CageFitter::takeMeanLoss() {
    float sum = 0.0f;
    for (float slot : loss_.read<float>()) sum += slot;
    loss_.clearToZero();
    const float mean = samplesSinceLoss_ > 0 ? sum / float(samplesSinceLoss_) : 0.0f;
    samplesSinceLoss_ = 0;
    return mean;
}

std::vector<glm::vec3> CageFitter::vertices() const {
    const auto values = vertices_.read();
    std::vector<glm::vec3> points(values.size() / 3);
    for (size_t i = 0; i < points.size(); ++i) points[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
    return points;
}

void CageFitter::setVertices(const std::vector<glm::vec3>& positions) {
    const auto values = flatten(positions);
    vertices_.theta.upload(values.data(), GLsizeiptr(values.size() * sizeof(float)));
}

CageFitter::State CageFitter::state() const {
    return {steps_, samples_, vertices_.adamSteps, vertices_.theta.read<float>(), vertices_.moment1.read<float>(),
            vertices_.moment2.read<float>()};
}

void CageFitter::restore(const State& state) {
    const size_t count = size_t(vertices_.count());
    if (state.theta.size() != count || state.moment1.size() != count || state.moment2.size() != count)
        throw Error("checkpoint holds " + std::to_string(state.theta.size()) + " vertex parameters, the cage has " +
                    std::to_string(count));
    const auto bytes = GLsizeiptr(count * sizeof(float));
    vertices_.theta.upload(state.theta.data(), bytes);
    vertices_.moment1.upload(state.moment1.data(), bytes);
    vertices_.moment2.upload(state.moment2.data(), bytes);
    vertices_.adamSteps = state.adamSteps;
    steps_ = state.steps;
    samples_ = state.samples;
}

void CageFitter::render(const render::Camera& camera, const render::RenderTarget& target) {
    stencils_.evaluate(programs_, vertices_.theta, pointsPlus_);
    renderer_.draw(programs_, pointsPlus_, camera, target);
}

}  // namespace subdfit::fit
