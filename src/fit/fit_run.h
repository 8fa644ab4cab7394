#pragma once
// One fit, step by step. `subdfit fit`, the stages of `simplify`, the viewer and the benchmarks
// all drive this, so the step, the resume rule, checkpoints and the report exist once.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "context/gl_context.h"
#include "fit/cage_fitter.h"
#include "fit/fit_report.h"
#include "fit/fit_scene.h"

namespace subdfit::fit {

struct Progress {
    int step, steps;
    float loss;
    double seconds, etaSeconds;
};

struct FitHooks {
    std::function<void(const Progress&)> progress{};
    const std::atomic<bool>* cancel = nullptr;  // set: stop at the next step, checkpointed
    std::function<void(const std::string& line)> note{};  // news for the user, e.g. "nothing to resume"
};

class FitRun {
public:
    // Builds the fitter and scores the starting state (the report's "before"). Needs the
    // scene's GL context current; `programs` and `scene` must outlive the run.
    FitRun(const FitOptions& options, gl::ProgramCache& programs, FitScene& scene);

    // Continues from `checkpoint` if it exists: true when it did. Throws subdfit::Error naming
    // the file when it is damaged or was written for other inputs or settings.
    bool resume(const std::filesystem::path& checkpoint);
    void saveCheckpoint(const std::filesystem::path& checkpoint);

    int step() const { return fitter_->stepsTaken(); }
    bool done() const { return step() >= options_.steps; }

    // One step: its views, its perturbation samples, the update. With `measureLoss` the step also
    // sums the loss, for takeMeanLoss().
    void advance(bool measureLoss);
    float takeMeanLoss() { return fitter_->takeMeanLoss(); }

    // Steps until `until` (clamped to the planned steps) or hooks.cancel: progress about 50
    // times a run, a checkpoint every options.checkpointEvery steps and at the end. True when
    // `until` was reached.
    bool runTo(int until, const std::filesystem::path& checkpoint, const FitHooks& hooks = {});

    // Scores the current state and writes cage.obj, the exports (fitted.glb, maps) and the
    // before / after / target PNGs of held-out view 0 into `out`, each atomically. report.json
    // is the caller's to write: toJson(report), plus what it adds.
    FitReport writeResults(const std::filesystem::path& out, const context::GlContext& context);

    // Rebuilds the fitter at another tessellation level, keeping its state and hand-set rates.
    void setTessLevel(int level);

    const FitOptions& options() const { return options_; }
    FitOptions& options() { return options_; }
    FitScene& scene() { return scene_; }
    CageFitter& fitter() { return *fitter_; }
    gl::ProgramCache& programs() { return programs_; }

private:
    FitOptions options_;
    gl::ProgramCache& programs_;
    FitScene& scene_;
    std::unique_ptr<CageFitter> fitter_;
    std::string fingerprint_;  // what a checkpoint must match
    int resumedFromStep_ = 0;
    std::chrono::steady_clock::time_point started_;
    double fitSeconds_ = 0.0;
    ViewSetScore trainBefore_, holdoutBefore_;
    std::vector<glm::vec4> beforeImage_;  // held-out view 0 before fitting
};

}  // namespace subdfit::fit
