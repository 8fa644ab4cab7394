#pragma once
// Fits the control vertices of one Catmull-Clark cage to a TargetSet with per-pixel SGE.
// One step: P (θ±), stencils(θ±), then per view R(θ+), R(θ−), G; then precondition and Adam.
// Everything stays on the GPU; only takeMeanLoss() and vertices() read back.
#include <cstdint>
#include <span>
#include <vector>

#include "gl/program_cache.h"
#include "mesh/polygon_mesh.h"
#include "render/patch_renderer.h"
#include "render/stencil_evaluator.h"
#include "scene/target_set.h"
#include "sge/passes.h"
#include "subdiv/patch_set.h"

namespace subdfit::fit {

struct CageFitSettings {
    sge::GroupSettings vertices{.sharedMoment = true};
    float smoothingLambda = 4.0f;   // λ of the (I + λL)⁻¹ gradient preconditioner
    int smoothingIterations = 8;    // Jacobi sweeps approximating that inverse
    int plannedSteps = 0;           // > 0: anneal the learning rate ×0.1 over this many steps
    int tessLevel = 8;              // segments per base-face edge
    int resolution = 256;
    std::uint32_t seed = 1;
};

class CageFitter {
public:
    // `cage` in the normalised scene frame.
    CageFitter(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const CageFitSettings& settings);

    // One optimisation step using the given training views of `targets`: accumulate + update.
    // With `measureLoss`, the step's mean loss is added to what takeMeanLoss() reports.
    void step(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss = true);

    // The two halves of a step. accumulate() adds one SGE sample (fresh signs) to the gradient;
    // update() preconditions it, applies Adam and clears it.
    void accumulate(const scene::TargetSet& targets, std::span<const int> views, bool measureLoss = true);
    void update();

    // The raw accumulated gradient (for tests and benchmarks), then cleared.
    std::vector<float> takeGradient();

    // Mean per-pixel loss over the measured samples since the last call (one readback).
    float takeMeanLoss();

    std::vector<glm::vec3> vertices() const;
    void setVertices(const std::vector<glm::vec3>& positions);
    int stepsTaken() const { return steps_; }
    int parameterCount() const { return vertices_.count(); }
    const subdiv::PatchSet& patches() const { return patches_; }
    const render::PatchRenderer& renderer() const { return renderer_; }

    // Renders the current (unperturbed) cage.
    void render(const render::Camera& camera, const render::RenderTarget& target);

    sge::GroupSettings& vertexSettings() { return vertices_.settings(); }

    // Everything a resumed run needs to continue exactly where this one stopped.
    struct State {
        int steps = 0;
        std::uint32_t samples = 0;
        int adamSteps = 0;
        std::vector<float> theta, moment1, moment2;
    };
    State state() const;
    void restore(const State& state);  // throws subdfit::Error if it does not fit this cage

private:
    gl::ProgramCache& programs_;
    CageFitSettings settings_;
    subdiv::PatchSet patches_;
    render::StencilEvaluator stencils_;
    render::PatchRenderer renderer_;
    sge::ParameterGroup vertices_;
    sge::FaceVertexTable faceVertices_;
    sge::Adjacency adjacency_;
    gl::Buffer pointsPlus_, pointsMinus_, smoothScratch_, loss_;
    render::RenderTarget plus_, minus_;
    int steps_ = 0, samplesSinceLoss_ = 0;
    std::uint32_t samples_ = 0;  // perturbation counter: one per accumulate()
};

}  // namespace subdfit::fit
