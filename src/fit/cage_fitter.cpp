#include "fit/cage_fitter.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mesh/mesh_adjacency.h"
#include "mesh/mesh_geometry.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

constexpr int kLossSlots = 256;             // see gradient.comp
constexpr int kMostFacesInAlpha = 1 << 24;  // every integer up to 2^24 is a float

std::vector<float> flatten(const std::vector<glm::vec3>& points) {
    std::vector<float> values;
    values.reserve(points.size() * 3);
    for (const auto& p : points) values.insert(values.end(), {p.x, p.y, p.z});
    return values;
}

optim::Adjacency uploadAdjacency(const mesh::PolygonMesh& cage) {
    const auto adjacency = mesh::vertexAdjacency(cage);
    return {gl::Buffer::fromVector(adjacency.offsets), gl::Buffer::fromVector(adjacency.neighbors), cage.vertexCount()};
}

// A cage drawn at a shallower isolation level (subdiv::drawingIsolationLevel) gets half the
// segments per face edge: its faces span a few pixels, and its deepest patches keep one each.
// With maps, every map cell gets at least one segment. The level counts segments per base-face
// edge, and a face that is not a quad splits into ptex faces of half its edges, each with a full
// map tile: such a cage needs twice the map resolution (drawn with only T/2 segments a ptex
// edge, the heights of every other node would be skipped between the vertices).
int tessLevelFor(const CageFitSettings& s, const mesh::PolygonMesh& cage) {
    const bool dense = subdiv::drawingIsolationLevel(cage) < subdiv::kIsolationLevel;
    const int segments = dense ? std::max(1, s.tessLevel / 2) : s.tessLevel;
    return s.mapEffects.geometric() ? std::max(segments, (mesh::hasNonQuadFaces(cage) ? 2 : 1) * s.maps.resolution)
                                    : segments;
}

}  // namespace

CageFitter::CageFitter(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const CageFitSettings& settings)
    : programs_(programs),
      settings_(settings),
      patches_(subdiv::cachedPatchSet(cage, {.isolationLevel = subdiv::drawingIsolationLevel(cage)})),
      stencils_(*patches_),
      renderer_(*patches_, tessLevelFor(settings, cage), settings.shading),
      vertices_(optim::GroupKind::Vertices, "vertices", flatten(cage.positions), settings.vertices),
      maps_(settings.mapEffects.any() ? std::make_unique<maps::MapParameters>(cage, settings.mapEffects, settings.maps)
                                      : nullptr),
      adjacency_(uploadAdjacency(cage)),
      // Only a fit that uses it pays for the relaxation's topology.
      relaxation_(settings.relaxation > 0.0f || settings.tangentialGradient < 1.0f
                      ? std::make_optional<CageRelaxation>(cage)
                      : std::nullopt),
      pointsPlus_(stencils_.makePointBuffer()),
      pointsMinus_(stencils_.makePointBuffer()),
      smoothScratch_(vertices_.gradient.bytes()),
      loss_(sizeof(float) * kLossSlots),
      surfacePlus_(renderer_.makeSurface()),
      surfaceMinus_(renderer_.makeSurface()),
      drawnPoints_(stencils_.makePointBuffer()),
      drawnSurface_(renderer_.makeSurface()),
      // Only a texel group's turn reads the renders' (u, v); G reads the face ids from alpha.
      plus_(settings.resolution, settings.resolution, {.patchUv = settings.mapEffects.any(), .faceInAlpha = true}),
      minus_(settings.resolution, settings.resolution, {.patchUv = settings.mapEffects.any(), .faceInAlpha = true}) {
    if (patches_->ptexFaceCount > kMostFacesInAlpha)
        throw Error("a cage of " + std::to_string(patches_->ptexFaceCount) + " ptex faces is past the " +
                    std::to_string(kMostFacesInAlpha) + " whose ids a float render target holds exactly");
}

std::vector<optim::ParameterGroup*> CageFitter::groups() {
    std::vector<optim::ParameterGroup*> out{&vertices_};
    if (maps_)
        for (auto* group : maps_->groups()) out.push_back(group);
    return out;
}

void CageFitter::step(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss) {
    accumulate(targets, views, measureLoss);
    update();
}

void CageFitter::accumulate(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss) {
    // A distinct counter per sample keeps every sample's signs independent; the seed separates runs.
    const std::uint32_t counter = samples_;
    const auto all = groups();
    const bool mapsStarted = steps_ >= mapsStartStep();
    // Once the maps have started, the vertices keep every other turn and the map groups share
    // the rest: the cage still sets the shape that the maps' detail sits on.
    std::vector<optim::ParameterGroup*> mapTurns;
    for (size_t k = 1; k < all.size(); ++k)
        if (optimised(*all[k])) mapTurns.push_back(all[k]);
    const bool verticesOn = optimised(vertices_);
    const bool mapsOn = !mapTurns.empty() && (mapsStarted || !verticesOn);
    optim::ParameterGroup* perturbed = nullptr;
    if (verticesOn && (!mapsOn || counter % 2 == 0)) perturbed = &vertices_;
    else if (mapsOn) perturbed = mapTurns[(verticesOn ? counter / 2 : counter) % mapTurns.size()];
    else return;  // nothing is optimised
    ++samples_;
    optim::perturb(programs_, *perturbed, counter, settings_.seed);
    mark("perturb");
    if (std::find(pendingUpdate_.begin(), pendingUpdate_.end(), perturbed) == pendingUpdate_.end())
        pendingUpdate_.push_back(perturbed);
    const bool verticesPerturbed = perturbed->kind() == optim::GroupKind::Vertices;
    const float pixels = float(settings_.resolution) * float(settings_.resolution);
    const auto mapsPlus = maps_ ? maps_->forRaster(maps::ParameterVersion::Plus, perturbed) : render::PatchMaps{};
    const auto mapsMinus = maps_ ? maps_->forRaster(maps::ParameterVersion::Minus, perturbed) : render::PatchMaps{};
    const render::PatchRenderer::Surface& minusSurface = evaluateSurfaces(*perturbed, mapsPlus, mapsMinus);
    for (int view : views) {
        const auto& camera = targets.camera(view);
        renderer_.rasterize(programs_, surfacePlus_, camera, plus_, &mapsPlus);
        mark("render θ+");
        renderer_.rasterize(programs_, minusSurface, camera, minus_, &mapsMinus);
        mark("render θ−");
        sge::accumulateGradient(
            programs_, *perturbed, faceVertices(),
            {&plus_, &minus_, &targets.colors(), view, counter, settings_.seed, 1.0f / (pixels * float(views.size())),
             measureLoss, maps_.get(), settings_.fullImageEstimator},
            loss_);
        mark("gradient G");
    }
    if (verticesPerturbed) {
        sge::scatterFaceDeltas(programs_, vertices_, faceVertices(), counter, settings_.seed,
                               settings_.fullImageEstimator);
        mark("scatter to vertices");
    }
    if (measureLoss) ++samplesSinceLoss_;
}

const render::PatchRenderer::Surface& CageFitter::evaluateSurfaces(const optim::ParameterGroup& perturbed,
                                                                   const render::PatchMaps& mapsPlus,
                                                                   const render::PatchMaps& mapsMinus) {
    const bool verticesPerturbed = perturbed.kind() == optim::GroupKind::Vertices;
    // A map's turn draws the cage as it is: while it stays (a map stage with the cage frozen),
    // its points are not evaluated again.
    const bool cageStayed = pointsPlusOf_ == vertices_.version();  // since the last map turn
    if (verticesPerturbed) {
        stencils_.evaluate(programs_, vertices_.thetaPlus, pointsPlus_, vertices_.thetaMinus, pointsMinus_);
        pointsPlusOf_.reset();
    } else if (!cageStayed) {
        stencils_.evaluate(programs_, vertices_.theta, pointsPlus_);
        pointsPlusOf_ = vertices_.version();
    }
    mark("stencils");
    // θ+ and θ− are one surface unless the turn moves it (the vertices or the heights): a map
    // that only shades is drawn on the surface evaluated once, for every view of the step, and
    // not evaluated again while the cage and the heights stay (one shading group's turn after
    // another's).
    const bool surfaceMoves = verticesPerturbed || (maps_ && &perturbed == maps_->displacement());
    const SurfaceKey key{vertices_.version(), maps_ && maps_->displacement() ? maps_->displacement()->version() : 0,
                         mapsPlus.limitShading};
    if (verticesPerturbed) {
        // A vertex turn draws both with the maps as they are: one set for the pair.
        renderer_.evaluatePair(programs_, pointsPlus_, surfacePlus_, pointsMinus_, surfaceMinus_, &mapsPlus);
    } else {
        if (surfaceMoves || surfacePlusOf_ != key) evaluateOnCage(mapsPlus, surfacePlus_, cageStayed);
        if (surfaceMoves) evaluateOnCage(mapsMinus, surfaceMinus_, cageStayed);
    }
    surfacePlusOf_ = surfaceMoves ? std::nullopt : std::make_optional(key);
    mark("surfaces");
    return surfaceMoves ? surfaceMinus_ : surfacePlus_;
}

void CageFitter::evaluateOnCage(const render::PatchMaps& maps, const render::PatchRenderer::Surface& surface,
                                bool cageStayed) {
    // Heights on a cage that stays (a map stage with the cage frozen): its limit surface is kept
    // and displaced by each set of them. A cage that moves between map turns is evaluated at once.
    if (!maps.kinds.has(kinds::MapKind::Displacement) || !cageStayed) {
        renderer_.evaluate(programs_, pointsPlus_, surface, &maps);
        return;
    }
    if (limitOf_ != vertices_.version()) {
        if (!limitVertices_) limitVertices_.emplace(renderer_.makeVertices());
        renderer_.evaluateLimit(programs_, pointsPlus_, *limitVertices_);
        limitOf_ = vertices_.version();
    }
    renderer_.displace(programs_, *limitVertices_, surface, maps);
}

sge::FaceVertexTable& CageFitter::faceVertices() {
    if (!faceVertices_)
        faceVertices_.emplace(patches_->faceVertexOffsets, patches_->faceVertexIndices, vertices_.count() / 3);
    return *faceVertices_;
}

float CageFitter::learningRateScale() const {
    if (scaleOverride_) return *scaleOverride_;
    // Exponential annealing to a tenth: large moves first, then settle within the noise.
    return settings_.plannedSteps > 0 ? std::pow(0.1f, std::min(1.0f, float(steps_) / float(settings_.plannedSteps)))
                                      : 1.0f;
}

void CageFitter::update() {
    const float scale = learningRateScale();
    for (auto* g : pendingUpdate_) {
        const float learningRate = g->settings().learningRate * scale;
        if (g->kind() == optim::GroupKind::Vertices) {
            updateVertices(learningRate * vertexRateFactor_);
            continue;
        }
        optim::resolveGradient(programs_, *g);
        mark("resolve");
        maps_->update(programs_, *g, learningRate);
        mark("Adam");
        g->gradientSum.clearToZero();  // only the groups sampled since the last update have sums
        mark("clear sums");
    }
    pendingUpdate_.clear();
    ++steps_;
}

void CageFitter::updateVertices(float learningRate) {
    const bool project = relaxation_ && settings_.tangentialGradient < 1.0f;
    if (optim::updatesInOneGroup(vertices_)) {
        const optim::TangentialProjection projection{[this] { relaxation_->bindTangentFrame(); },
                                                     settings_.tangentialGradient};
        optim::updateVertices(programs_, vertices_, adjacency_, settings_.smoothingLambda,
                              settings_.smoothingIterations, project ? &projection : nullptr, learningRate);
        mark("update");
    } else {
        optim::resolveGradient(programs_, vertices_);
        mark("resolve");
        optim::precondition(programs_, vertices_, adjacency_, settings_.smoothingLambda, settings_.smoothingIterations,
                            smoothScratch_);
        mark("precondition");
        if (project)
            relaxation_->projectGradient(programs_, vertices_.theta, vertices_.gradientSmooth,
                                         settings_.tangentialGradient);
        optim::adamStep(programs_, vertices_, vertices_.gradientSmooth, learningRate);
        mark("Adam");
        vertices_.gradientSum.clearToZero();
        mark("clear sums");
    }
    if (relaxation_) {
        relaxation_->apply(programs_, vertices_.theta, settings_.relaxation);
        vertices_.changed();
    }
}

void CageFitter::setRates(optim::ParameterGroup& group, float epsilon, float learningRate) {
    group.settings().epsilon = epsilon;
    group.settings().learningRate = learningRate;
}

bool CageFitter::optimised(const optim::ParameterGroup& group) const {
    return std::find(frozen_.begin(), frozen_.end(), &group) == frozen_.end();
}

void CageFitter::setOptimised(const optim::ParameterGroup& group, bool on) {
    std::erase(frozen_, &group);
    if (!on) frozen_.push_back(&group);
}

std::vector<float> CageFitter::accumulatedGradient() {
    optim::resolveGradient(programs_, vertices_);
    return vertices_.gradient.read<float>();
}

std::vector<float> CageFitter::takeGradient() {
    auto gradient = accumulatedGradient();
    vertices_.gradientSum.clearToZero();
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

surface::SurfaceMaps CageFitter::surfaceMaps() {
    surface::SurfaceMaps maps;
    if (!maps_) return maps;
    maps.layout = maps_->layout();
    maps.appearanceLayout = maps_->appearanceLayout();
    maps.appearanceAtlas = maps_->appearanceAtlas();
    maps_->readCarriedTextures(maps);
    maps.shadingNormal = maps_->shadingNormal();
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds) {
        const optim::ParameterGroup* g = maps_->group(kind.kind);
        if (!g) continue;
        std::vector<float>& values = maps.values(kind.kind) = g->read();
        if (kind.unitRange)  // what the renderer reads them as
            for (float& v : values) v = std::clamp(v, 0.0f, 1.0f);
    }
    return maps;
}

std::vector<glm::vec3> CageFitter::vertices() const {
    const auto values = vertices_.read();
    std::vector<glm::vec3> points(values.size() / 3);
    for (size_t i = 0; i < points.size(); ++i) points[i] = {values[3 * i], values[3 * i + 1], values[3 * i + 2]};
    return points;
}

int CageFitter::mapsStartStep() const {
    if (mapsStartOverride_) return *mapsStartOverride_;
    if (settings_.plannedSteps <= 0) return 0;
    return int(std::ceil(settings_.mapsStartFraction * float(settings_.plannedSteps)));
}

void CageFitter::setVertices(const std::vector<glm::vec3>& positions) { vertices_.write(flatten(positions)); }

CageFitter::State CageFitter::state() {
    State state{.steps = steps_, .samples = samples_};
    for (auto* g : groups())
        state.groups.push_back({g->theta.read<float>(), g->moment1.read<float>(), g->moment2.read<float>(),
                                g->groupMoment2.read<float>().at(0), g->adamSteps});
    state.learningRateScale = scaleOverride_.value_or(-1.0f);
    state.mapsStartStep = mapsStartOverride_.value_or(-1);
    return state;
}

void CageFitter::restore(const State& state) {
    auto all = groups();
    if (state.groups.size() != all.size())
        throw Error("checkpoint holds " + std::to_string(state.groups.size()) + " parameter groups, the scene has " +
                    std::to_string(all.size()));
    for (size_t k = 0; k < all.size(); ++k) {
        auto& g = *all[k];
        const auto& saved = state.groups[k];
        const size_t count = size_t(g.count());
        if (saved.theta.size() != count || saved.moment1.size() != count || saved.moment2.size() != count)
            throw Error("checkpoint group '" + g.name() + "' holds " + std::to_string(saved.theta.size()) +
                        " parameters, the scene has " + std::to_string(count));
        const auto bytes = GLsizeiptr(count * sizeof(float));
        g.write(saved.theta);
        g.moment1.upload(saved.moment1.data(), bytes);
        g.moment2.upload(saved.moment2.data(), bytes);
        g.groupMoment2.upload(&saved.groupMoment2, sizeof(float));
        g.adamSteps = saved.adamSteps;
    }
    steps_ = state.steps;
    samples_ = state.samples;
    scaleOverride_ = state.learningRateScale >= 0.0f ? std::optional<float>(state.learningRateScale) : std::nullopt;
    mapsStartOverride_ = state.mapsStartStep >= 0 ? std::optional<int>(state.mapsStartStep) : std::nullopt;
}

void CageFitter::render(const render::Camera& camera, const render::RenderTarget& target) {
    // θ read back and compared rather than tracked: a step, a restore or a write from outside
    // all show in it.
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the optimiser's shader writes, seen by the read
    const auto maps = maps_ ? maps_->forRaster(maps::ParameterVersion::Current) : render::PatchMaps{};
    DrawnSurfaceKey key{.vertices = vertices_.read(), .limitShading = maps.limitShading};
    if (maps_ && maps_->displacement()) key.heights = maps_->displacement()->read();
    if (key != drawnFrom_) {
        stencils_.evaluate(programs_, vertices_.theta, drawnPoints_);
        renderer_.evaluate(programs_, drawnPoints_, drawnSurface_, &maps);
        drawnFrom_ = std::move(key);
    }
    renderer_.rasterize(programs_, drawnSurface_, camera, target, &maps);
}

}  // namespace subdfit::fit
