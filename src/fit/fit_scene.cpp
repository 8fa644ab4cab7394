#include "fit/fit_scene.h"

#include <algorithm>
#include <cmath>

#include "fit/image_metrics.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"
#include "util/parallel_for.h"

namespace subdfit::fit {
namespace {

constexpr int kMonitorViews = 4;
constexpr float kFramedWidth = 2.3f;  // normalised units across the rendered view
constexpr float kEpsilonPixels = 0.9f, kStepPixels = 0.45f;
// And never more than this in the normalised frame, whatever the resolution: beyond it a coarse
// cage's few vertices each move so much surface per step that the estimate stops pointing
// downhill.
constexpr float kEpsilonMax = 0.008f, kStepMax = 0.004f;
// The cage edge (a quarter of the scene radius) at and above which --smoothing is λ itself.
constexpr float kReferenceEdge = 0.25f;
// A coarse cage's faces span many pixels: drawn with too few segments, its facets, not its
// shape, would set the loss. No segment spans more than this many pixels of a mean edge.
constexpr float kSegmentPixels = 4.0f;
// A displacement step moves a height by at most this fraction of a map cell's width: what the
// images see of a height is mostly its slope (the shading normal), and a step that tilts every
// normal by a few degrees turns the estimator's noise into a rough, darkened surface.
constexpr float kHeightStepSlope = 0.03f;

mesh::PolygonMesh normalized(mesh::PolygonMesh mesh, const scene::SceneFrame& frame) {
    mesh.positions = frame.toNormalized(mesh.positions);
    return mesh;
}

// The frame is the reference's: its failures are about that file.
scene::SceneFrame frameOf(const mesh::PolygonMesh& reference) {
    try {
        return scene::frameAround(reference.positions);
    } catch (const Error& e) {
        throw fileError(reference.sourcePath, e.what());
    }
}

}  // namespace

render::ShadingModel shadingOf(const FitOptions& o, const mesh::PolygonMesh& reference) {
    return o.shading ? *o.shading : render::shadingFor(reference);
}

maps::MapEffects mapEffectsOf(const FitOptions& o, render::ShadingModel shading) {
    return o.maps | maps::appearanceFor(shading);
}

FitScene::FitScene(const ResolvedFitOptions& options, gl::ProgramCache& programs)
    : FitScene(options, programs, mesh::loadMesh(options->cage), mesh::loadReference(options->reference)) {}

FitScene::FitScene(const ResolvedFitOptions& resolvedOptions, gl::ProgramCache& programs, mesh::PolygonMesh cageWorldIn,
                   const mesh::PolygonMesh& referenceWorld)
    : FitScene(*resolvedOptions, programs, std::move(cageWorldIn), referenceWorld, Checked{}) {}

FitScene::FitScene(const FitOptions& o, gl::ProgramCache& programs, mesh::PolygonMesh cageWorldIn,
                   const mesh::PolygonMesh& referenceWorld, Checked)
    : frame(frameOf(referenceWorld)),
      shading(shadingOf(o, referenceWorld)),
      cageWorld(std::move(cageWorldIn)),
      cage(normalized(cageWorld, frame)),
      reference(normalized(mesh::triangulated(referenceWorld), frame)),
      referenceRenderer(reference, shading),
      training(programs, referenceRenderer, render::orbitCameras(o.views, o.seed), o.resolution),
      holdout(programs, referenceRenderer, render::orbitCameras(o.holdoutViews, o.seed ^ 0x9e3779b9u), o.resolution,
              kViewerSupersampling),
      monitor(programs, referenceRenderer, render::orbitCameras(kMonitorViews, o.seed ^ 0x85ebca6bu), o.resolution) {}

const scene::TargetSet& FitScene::choosing(gl::ProgramCache& programs) const {
    if (!choosing_) {
        std::vector<render::Camera> cameras;
        for (int v = 0; v < monitor.size(); ++v) cameras.push_back(monitor.camera(v));
        choosing_ = std::make_unique<scene::TargetSet>(programs, referenceRenderer, std::move(cameras),
                                                       monitor.resolution(), kViewerSupersampling);
    }
    return *choosing_;
}

void FitScene::setCage(mesh::PolygonMesh cageWorldIn) {
    cageWorld = std::move(cageWorldIn);
    cage = normalized(cageWorld, frame);
}

CageFitSettings fitSettings(const FitOptions& o, const mesh::PolygonMesh& cage, render::ShadingModel shading) {
    CageFitSettings settings;
    // A dense cage needs steps in proportion to its edges, or neighbours jitter against each
    // other and the cage crumples; a coarse one is limited by what the images resolve: a
    // perturbation of about a pixel, steps of about half a pixel, where a pixel spans the
    // framed view (the unit sphere plus a margin, render/camera.cpp) over the resolution, and
    // by the absolute caps above.
    const float edge = mesh::meanEdgeLength(cage);
    const float pixel = kFramedWidth / float(o.resolution);
    settings.vertices.epsilon = std::min({o.epsilon * edge, kEpsilonPixels * pixel, kEpsilonMax});
    settings.vertices.learningRate = std::min({o.learningRate * edge, kStepPixels * pixel, kStepMax});
    // λ counts in cage edges; what must be pooled is a neighbourhood of the surface (enough
    // pixels per estimate), so on a cage denser than the reference one λ grows as the square of
    // the density, and the Jacobi sweeps with its reach (about sqrt(λ) edges). A coarser cage
    // keeps λ: its few vertices each see plenty of pixels, but need the coupling to move
    // together rather than jitter apart.
    const float density = std::max(1.0f, kReferenceEdge / edge);
    settings.smoothingLambda = o.smoothing * density * density;
    settings.smoothingIterations = std::clamp(int(std::lround(8.0 * std::sqrt(settings.smoothingLambda / 4.0))), 8, 48);
    settings.vertices.noiseGate = o.noiseGate;
    for (optim::GroupSettings& group : settings.maps.groups) group.noiseGate = o.noiseGate;
    settings.relaxation = o.relaxation;
    settings.tangentialGradient = o.tangential;
    settings.tessLevel = std::max(o.tessLevel, screenSegments(cage, o.resolution, kSegmentPixels));
    settings.resolution = o.resolution;
    settings.seed = o.seed;
    settings.plannedSteps = o.steps;
    settings.mapEffects = mapEffectsOf(o, shading);
    settings.shading = shading;
    settings.maps.resolution = o.mapResolution;
    optim::GroupSettings& heights = settings.maps.of(maps::MapKind::Displacement);
    heights.learningRate =
        std::min(heights.learningRate, kHeightStepSlope * edge / float(std::max(1, o.mapResolution)));
    settings.maps.appearanceResolution = o.appearanceResolution;
    settings.maps.appearanceAtlas = o.appearanceAtlas;
    settings.maps.shadingNormal = o.shadingNormal;
    settings.mapsStartFraction = o.mapsStart;
    return settings;
}

int screenSegments(const mesh::PolygonMesh& cage, int resolution, float pixels) {
    const float pixel = kFramedWidth / float(resolution);
    return std::max(1, int(std::ceil(mesh::meanEdgeLength(cage) / (pixels * pixel))));
}

FitOptions withVertexRates(FitOptions options, const mesh::PolygonMesh& cage, const optim::GroupSettings& vertices) {
    const optim::GroupSettings given = fitSettings(options, cage).vertices;
    const float edge = mesh::meanEdgeLength(cage);
    if (vertices.epsilon != given.epsilon) options.epsilon = vertices.epsilon / edge;
    if (vertices.learningRate != given.learningRate) options.learningRate = vertices.learningRate / edge;
    return options;
}

ViewSetScore score(const scene::TargetSet& targets, const scene::TargetSet::Draw& draw) {
    double loss = 0.0;
    for (int i = 0; i < targets.size(); ++i) loss += targets.loss(i, draw);
    loss /= std::max(1, targets.size());
    return {loss, psnrFromLoss(loss)};
}

ViewSetScore score(CageFitter& fitter, const scene::TargetSet& targets) {
    return score(targets, [&](const render::Camera& camera, const render::RenderTarget& canvas) {
        fitter.render(camera, canvas);
    });
}

HoldoutScore scoreHoldout(const scene::TargetSet& holdout, const scene::TargetSet::Draw& draw) {
    HoldoutScore score;
    const int views = holdout.size();
    std::vector<std::vector<glm::vec4>> drawn(static_cast<size_t>(views)), targets(static_cast<size_t>(views));
    for (int i = 0; i < views; ++i) {
        drawn[size_t(i)] = holdout.render(i, draw);
        targets[size_t(i)] = holdout.readColor(i);
        const double viewLoss = meanPixelLoss(drawn[size_t(i)], targets[size_t(i)]);
        score.loss += viewLoss;
        score.psnrViews.push_back(psnrFromLoss(viewLoss));
    }
    // SSIM is CPU work (blurs of every image): the views' on every core, once all are drawn.
    std::vector<double> similarity(static_cast<size_t>(views));
    parallelFor(0, views, [&](int i) {
        similarity[size_t(i)] =
            structuralSimilarity(drawn[size_t(i)], targets[size_t(i)], holdout.resolution(), holdout.resolution());
    });
    if (views > 0) score.firstView = std::move(drawn[0]);
    score.loss /= std::max(1, views);
    score.psnr = psnrFromLoss(score.loss);
    for (double s : similarity) score.ssim += s;
    score.ssim /= std::max(1, views);
    return score;
}

HoldoutScore scoreHoldout(CageFitter& fitter, const scene::TargetSet& holdout) {
    return scoreHoldout(holdout, [&](const render::Camera& camera, const render::RenderTarget& canvas) {
        fitter.render(camera, canvas);
    });
}

}  // namespace subdfit::fit
