#pragma once
// A small fitting scene for GL tests: a cage and a reference, both in the normalised frame of
// the reference, with targets rendered from a few views.
#include <filesystem>
#include <memory>
#include <random>

#include "fit/cage_fitter.h"
#include "fit/finite_differences.h"
#include "fit/fit_options.h"
#include "mesh/mesh_loader.h"
#include "render/mesh_renderer.h"
#include "scene/scene_frame.h"
#include "scene/target_set.h"

namespace subdfit::test {

struct FitScene {
    mesh::PolygonMesh cage, reference;
    std::unique_ptr<render::MeshRenderer> referenceRenderer;
    std::unique_ptr<scene::TargetSet> targets;
};

inline FitScene makeFitScene(gl::ProgramCache& programs, mesh::PolygonMesh cage, mesh::PolygonMesh reference, int views,
                             int resolution, std::uint32_t seed = 1) {
    FitScene s;
    reference = mesh::triangulated(reference);
    const auto frame = scene::frameAround(reference.positions);
    cage.positions = frame.toNormalized(cage.positions);
    reference.positions = frame.toNormalized(reference.positions);
    s.referenceRenderer = std::make_unique<render::MeshRenderer>(
        reference.positions, mesh::vertexNormals(reference),
        std::vector<unsigned>(reference.faceIndices.begin(), reference.faceIndices.end()));
    s.targets = std::make_unique<scene::TargetSet>(programs, *s.referenceRenderer, render::orbitCameras(views, seed),
                                                   resolution);
    s.cage = std::move(cage);
    s.reference = std::move(reference);
    return s;
}

// A quick fit's options: 6 training views and 2 held out at 48², `steps` steps, results in `dir`.
inline fit::FitOptions smallFitOptions(const std::filesystem::path& dir, int steps) {
    fit::FitOptions o;
    o.out = dir;
    o.steps = steps;
    o.views = 6;
    o.holdoutViews = 2;
    o.resolution = 48;
    return o;
}

// Σ over views and pixels of ‖I − T‖²: the unnormalised loss whose gradient G estimates.
inline double totalLoss(fit::CageFitter& fitter, const scene::TargetSet& targets) {
    return fit::totalImageLoss(fitter, targets);
}

inline std::vector<glm::vec3> noised(std::vector<glm::vec3> points, float sigma, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal(0.0f, sigma);
    for (auto& p : points) p += glm::vec3(normal(rng), normal(rng), normal(rng));
    return points;
}

inline double rmsDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    double sum = 0.0;
    for (size_t i = 0; i < a.size(); ++i) sum += double(glm::dot(a[i] - b[i], a[i] - b[i]));
    return std::sqrt(sum / double(std::max<size_t>(1, a.size())));
}

// The largest distance between corresponding points (same count).
inline float maxDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    float worst = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, glm::length(a[i] - b[i]));
    return worst;
}

}  // namespace subdfit::test
