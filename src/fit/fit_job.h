#pragma once
// `subdfit fit`: load a cage and a reference, render targets, fit the cage's control vertices
// (and maps), write cage.obj, the exports, report.json and before/after/target images of a
// held-out view into a folder. The pieces are public for `simplify` and the viewer, which run
// the same fit on a cage of their own or step by step.
#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "context/gl_context.h"
#include "fit/fit_scene.h"

namespace subdfit::fit {

struct Progress {
    int step, steps;
    float loss;
    double seconds, etaSeconds;
};

using ProgressSink = std::function<void(const Progress&)>;

// Called once the fitted cage and its exports are written (`exports`: {file name: bytes}), before
// report.json; what it returns is merged into the report, and it may write files of its own
// into options.out.
using FitEvaluation = std::function<nlohmann::json(CageFitter&, FitScene&, const nlohmann::json& exports)>;

// Called once per run when the maps join the fit: at that step (`restored` false: e.g. set the
// maps' θ from the cage as fitted so far), or at the first step of a run resumed past it
// (`restored` true: θ came from the checkpoint, settings changed at the start must be redone).
using MapsStart = std::function<void(CageFitter&, FitScene&, bool restored)>;

struct FitHooks {
    ProgressSink progress{};
    const std::atomic<bool>* cancel = nullptr;  // set during the fit: stop at the next step, checkpointed
    FitEvaluation evaluate{};
    MapsStart onMapsStart{};
    std::function<void(const std::string& line)> note{};  // news for the user, e.g. "nothing to resume"
};

// What a folder of fit results holds, so that a later run may write there again
// (io::checkOutputFolder).
inline const std::vector<std::string> kFitResultMarkers = {"report.json", "checkpoint.bin"};

// Checks the output folder, loads the inputs, fits and writes the results. Interrupted (hooks
// .cancel), it still writes the results of the steps taken. Throws subdfit::Error for bad
// options or inputs before anything is written.
nlohmann::json runFit(const FitOptions& options, const FitHooks& hooks = {});

// The same on a scene built by the caller in the current context.
nlohmann::json runFit(const FitOptions& options, gl::ProgramCache& programs, const context::GlContext& context,
                      FitScene& scene, const FitHooks& hooks = {});

// What a report says about the run beyond the fitted scene itself.
struct FitHistory {
    int firstStep = 0, steps = 0;
    double seconds = 0.0, fitSeconds = 0.0;
    ViewSetScore trainBefore, holdoutBefore;
    std::vector<glm::vec4> beforeImage;  // held-out view 0 before fitting

    bool interrupted(const FitOptions& o) const { return steps < o.steps; }
};

// The optimisation alone: scores the starting state, resumes from `checkpoint` when
// options.resume asks (saying so through hooks.note when there is none), runs the steps up to
// options.steps or until hooks.cancel, and leaves a checkpoint of where it stopped.
FitHistory fitSteps(const FitOptions& options, FitScene& scene, CageFitter& fitter,
                    const std::filesystem::path& checkpoint, const FitHooks& hooks = {});

// Scores the fitter's current scene and writes cage.obj, the exports, before/after/target PNGs
// and report.json (with what `evaluate` adds) into options.out, each file atomically. Returns
// the report.
nlohmann::json writeFitResults(const FitOptions& options, gl::ProgramCache& programs,
                               const context::GlContext& context, FitScene& scene, CageFitter& fitter,
                               const FitHistory& history, const FitEvaluation& evaluate = {});

}  // namespace subdfit::fit
