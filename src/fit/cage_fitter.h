#pragma once
// Fits a Catmull-Clark cage (its control vertices, and the displacement / normal maps when the
// scene has them) to a TargetSet with per-pixel SGE. One step: P (θ± of one group), stencils,
// then per view R(θ+), R(θ−), G; then Adam on that group (after the vertex preconditioner).
//
// Groups take turns, one per sample (vertices every other turn, the map groups sharing the
// rest): perturbing the vertices moves silhouettes and shading far more than a texel does, so a
// joint perturbation would drown each texel's estimate in the vertices' noise; in turn, each
// group's estimate only carries its own group's cross terms.
// Everything stays on the GPU; only takeMeanLoss(), state() and the readers read back.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fit/cage_relaxation.h"
#include "fit/fit_state.h"
#include "gl/program_cache.h"
#include "gl/timestamp_log.h"
#include "maps/map_parameters.h"
#include "mesh/polygon_mesh.h"
#include "render/patch_renderer.h"
#include "render/stencil_evaluator.h"
#include "scene/target_set.h"
#include "sge/passes.h"
#include "subdiv/patch_set.h"
#include "surface/surface_maps.h"

namespace subdfit::fit {

struct CageFitSettings {
    optim::GroupSettings vertices{.sharedMoment = true};
    float smoothingLambda = 4.0f;  // λ of the (I + λL)⁻¹ vertex-gradient preconditioner
    int smoothingIterations = 8;   // damped Jacobi sweeps approximating that inverse
    // Per vertex update, the fraction of the way each vertex slides within its tangent plane
    // towards its neighbours (fit/cage_relaxation.h); 0: off.
    float relaxation = 0.0f;
    // The fraction of the vertex gradient's tangential part kept (1: all of it).
    float tangentialGradient = 1.0f;
    int plannedSteps = 0;  // > 0: anneal every learning rate ×0.1 over this many steps
    int tessLevel = 8;     // segments per base-face edge (at least the map resolution)
    int resolution = 256;
    std::uint32_t seed = 1;
    maps::MapEffects mapEffects{};  // which texel groups exist at all
    render::ShadingModel shading = render::ShadingModel::Geometry;
    // Coarse to fine: the maps join the turns only after this fraction of plannedSteps, once
    // the cage has its shape (detail fitted on a wrong shape would be undone later).
    float mapsStartFraction = 0.4f;
    maps::MapSettings maps{};
    // Plain full-image SPSA instead of the per-pixel estimator: for benchmarks that show why not.
    bool fullImageEstimator = false;
};

class CageFitter {
public:
    // `cage` in the normalised scene frame.
    CageFitter(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const CageFitSettings& settings);

    // One optimisation step using the given training views of `targets`: accumulate + update.
    // With `measureLoss`, the step's mean loss is added to what takeMeanLoss() reports.
    void step(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss = true);

    // The two halves of a step. accumulate() adds one SGE sample (fresh signs) to the gradient
    // of the group whose turn it is; update() applies Adam to the groups sampled since the last
    // update (preconditioning the vertex gradient) and clears every gradient.
    void accumulate(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss = true);
    void update();

    // The raw vertex gradient accumulated so far (for tests and benchmarks); take also clears it.
    std::vector<float> accumulatedGradient();
    std::vector<float> takeGradient();

    // Mean per-pixel loss over the measured samples since the last call (one readback).
    float takeMeanLoss();

    std::vector<glm::vec3> vertices() const;
    void setVertices(const std::vector<glm::vec3>& positions);
    int stepsTaken() const { return steps_; }
    // GPU timestamps at the end of each phase of a step (benchmarks); null: none.
    void setTimestampLog(gl::TimestampLog* log) { timestamps_ = log; }
    // The first step at which the map groups take turns (0 without a plan).
    int mapsStartStep() const;
    const subdiv::PatchSet& patches() const { return *patches_; }
    const render::PatchRenderer& renderer() const { return renderer_; }
    optim::ParameterGroup& vertexGroup() { return vertices_; }
    // Null when the scene has no maps.
    maps::MapParameters* maps() { return maps_.get(); }
    // The maps' current values on the CPU (normalised units), for the CPU twin of the surface
    // (surface/displaced_surface.h); no layout and no values when the scene has no maps.
    surface::SurfaceMaps surfaceMaps();
    // Every optimised group, vertices first.
    std::vector<optim::ParameterGroup*> groups();

    // Knobs for an interactive run (the viewer) and for simplify's stages, between steps: the
    // group's settings hold its ε (from the next sample on) and its learning rate before
    // annealing; update() multiplies the latter by learningRateScale().
    void setRates(optim::ParameterGroup& group, float epsilon, float learningRate);
    // The factor update() applies to every learning rate: a schedule's when one set it, else
    // exponential annealing to a tenth over the planned steps.
    float learningRateScale() const;
    void setLearningRateScale(float scale) { scaleOverride_ = scale; }
    // A further factor on the vertices' learning rate alone (a schedule's: the step the cage had
    // reached when the maps joined from zero at the full step).
    void setVertexRateFactor(float factor) { vertexRateFactor_ = factor; }
    float vertexRateFactor() const { return vertexRateFactor_; }
    // The maps join from the next step on (a stage that converged before their planned start).
    void startMapsNow() { mapsStartOverride_ = steps_; }
    // A group left out of the turns keeps its θ and Adam moments until it is optimised again.
    // With the vertices left out, the map groups take every turn, even before their start.
    bool optimised(const optim::ParameterGroup& group) const;
    void setOptimised(const optim::ParameterGroup& group, bool on);

    // Renders the current (unperturbed) scene. Scoring draws one θ on many views: its surface is
    // evaluated once, for as long as the vertices and heights stay bit for bit what it was
    // evaluated from.
    void render(const render::Camera& camera, const render::RenderTarget& target);
    // The next render() evaluates its surface anew, as a forward renderer of a scene that
    // changes between frames does (benchmarks).
    void forgetDrawnSurface() { drawnFrom_.reset(); }

    // Everything a resumed run needs to continue exactly where this one stopped.
    using GroupState = fit::GroupState;
    using State = FitState;
    State state();
    void restore(const State& state);  // throws subdfit::Error if it does not fit this scene

private:
    sge::FaceVertexTable& faceVertices();
    // θ+'s surface into surfacePlus_ and θ−'s (the one returned) for a turn of `perturbed`,
    // evaluating only what changed since the last turn.
    const render::PatchRenderer::Surface& evaluateSurfaces(const optim::ParameterGroup& perturbed,
                                                           const render::PatchMaps& mapsPlus,
                                                           const render::PatchMaps& mapsMinus);
    // A surface on the cage as it is (pointsPlus_) with `maps`' heights, into `surface`.
    void evaluateOnCage(const render::PatchMaps& maps, const render::PatchRenderer::Surface& surface, bool cageStayed);
    // Adam on the vertices from their sums (preconditioned, projected), then the relaxation: a
    // small cage's in one dispatch (optim::updateVertices), a larger one's pass by pass.
    void updateVertices(float learningRate);
    void mark(const char* phase) {
        if (timestamps_) timestamps_->mark(phase);
    }

    gl::TimestampLog* timestamps_ = nullptr;
    std::optional<float> scaleOverride_;
    float vertexRateFactor_ = 1.0f;
    std::optional<int> mapsStartOverride_;

    gl::ProgramCache& programs_;
    CageFitSettings settings_;
    std::shared_ptr<const subdiv::PatchSet>
        patches_;  // shared with fitters of the same topology (subdiv/table_cache.h)
    render::StencilEvaluator stencils_;
    render::PatchRenderer renderer_;
    optim::ParameterGroup vertices_;
    std::unique_ptr<maps::MapParameters> maps_;
    // Built at the first step: a fitter that only draws (a judged candidate, a score) needs none.
    std::optional<sge::FaceVertexTable> faceVertices_;
    optim::Adjacency adjacency_;
    std::optional<CageRelaxation> relaxation_;  // with --relax, or --tangential under 1 (the default)
    gl::Buffer pointsPlus_, pointsMinus_, smoothScratch_, loss_;
    render::PatchRenderer::Surface surfacePlus_, surfaceMinus_;  // a step's (render::PatchRenderer::evaluate)
    // The versions of θ a map's turn evaluated pointsPlus_ (the cage's) and surfacePlus_ (the
    // cage's and the heights') from; none after a turn that perturbed them.
    struct SurfaceKey {
        std::uint64_t vertices, heights;
        bool limitShading;
        bool operator==(const SurfaceKey&) const = default;
    };
    std::optional<std::uint64_t> pointsPlusOf_;
    std::optional<SurfaceKey> surfacePlusOf_;
    // The cage's limit surface without heights, kept for a map stage on a frozen cage (its version).
    std::optional<gl::Buffer> limitVertices_;
    std::optional<std::uint64_t> limitOf_;
    // render()'s points and surface, and what they were evaluated from (none yet: empty).
    struct DrawnSurfaceKey {
        std::vector<float> vertices{}, heights{};
        bool limitShading = false;
        bool operator==(const DrawnSurfaceKey&) const = default;
    };
    gl::Buffer drawnPoints_;
    render::PatchRenderer::Surface drawnSurface_;
    std::optional<DrawnSurfaceKey> drawnFrom_;
    render::RenderTarget plus_, minus_;
    int steps_ = 0, samplesSinceLoss_ = 0;
    std::uint32_t samples_ = 0;                          // perturbation counter: one per accumulate()
    std::vector<optim::ParameterGroup*> pendingUpdate_;  // groups perturbed since the last update()
    std::vector<const optim::ParameterGroup*> frozen_;   // groups left out of the turns
};

}  // namespace subdfit::fit
