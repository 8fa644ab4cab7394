#pragma once
// One fit as the viewer runs it: a FitRun (the scene and fitter of `subdfit fit`, the same steps,
// views and samples) stepped one step at a time, with the loss of every step kept for the curve.
// Needs a current GL context; every GL object it holds dies with it.
#include <memory>
#include <optional>
#include <vector>

#include "fit/fit_run.h"
#include "mesh/polygon_mesh.h"
#include "result_scene.h"

namespace subdfit::view {

struct FitInputs {
    mesh::PolygonMesh cage, reference;
    std::optional<surface::SurfaceMaps> start{};  // maps to start from (world units, on `cage`): a result refined
};

// Reads options.cage and options.reference (no GL needed, so a bad file is refused before a
// window opens). Throws subdfit::Error "path: problem".
FitInputs loadFitInputs(const fit::FitOptions& options);

// A fit that goes on from a result folder's asset (`result` read by loadResultInputs): its cage
// and maps against its reference. Sets what `options` must say for them (cage, reference, maps,
// their lattices and coding, the maps optimised from the first step). Throws subdfit::Error
// when the result has no reference or no asset.subd to refine.
FitInputs refineInputs(const ResultInputs& result, fit::FitOptions& options);

class FitSession {
public:
    // Throws subdfit::Error for bad options, inputs or a checkpoint that does not fit (--resume).
    FitSession(const fit::FitOptions& options, FitInputs inputs);

    const fit::FitOptions& options() const { return run_->options(); }
    fit::FitScene& scene() { return *scene_; }
    fit::CageFitter& fitter() { return run_->fitter(); }
    gl::ProgramCache& programs() { return programs_; }
    float meanEdge() const {
        return meanEdge_;
    }  // of the cage in the fit's frame: the unit of the vertex knobs' options

    // One step, its mean loss measured and kept; none while no group is optimised.
    void step();
    int stepsTaken() const { return run_->step(); }
    const std::vector<float>& losses() const { return losses_; }
    bool anythingOptimised();

    // Rebuilds the fitter for another tessellation level, keeping its state and knobs.
    void setTessLevel(int level) { run_->setTessLevel(level); }

    // The outputs of `subdfit fit` (and checkpoint.bin, so `subdfit fit --resume` can go on)
    // into `out`. Returns report.json's contents.
    nlohmann::json save(const context::GlContext& context, const std::filesystem::path& out);

private:
    gl::ProgramCache programs_;
    std::unique_ptr<fit::FitScene> scene_;
    std::unique_ptr<fit::FitRun> run_;
    std::vector<float> losses_;
    float meanEdge_ = 0.0f;
};

}  // namespace subdfit::view
