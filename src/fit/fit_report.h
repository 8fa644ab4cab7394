#pragma once
// What one fit did and how well it did, typed: apps and benchmarks read fields, and report.json
// is made from it in one place (toJson).
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "context/gl_context.h"
#include "fit/fit_options.h"
#include "fit/fit_state.h"
#include "gl/program_cache.h"
#include "maps/map_parameters.h"

namespace subdfit::fit {

struct ViewSetScore {
    double loss = 0.0, psnr = 0.0;
};

// The held-out views as a report shows them: besides the mean loss and its PSNR, each view's
// PSNR (one bad view can decide the mean, and this says which), their mean SSIM, and view 0 as
// drawn (before.png, after.png, the comparison image).
struct HoldoutScore : ViewSetScore {
    std::vector<double> psnrViews;
    double ssim = 0.0;
    std::vector<glm::vec4> firstView;
};

struct FitReport {
    FitOptions options;                                   // as run: settings and paths
    int steps = 0;                                        // steps taken in all, those before a resume included
    int resumedFromStep = 0;                              // 0 when not resumed
    double seconds = 0.0;                                 // the whole run: scene, fit, scoring
    double fitSeconds = 0.0;                              // the steps alone
    std::optional<ViewSetScore> trainBefore, trainAfter;  // none where the run was not asked for them
    HoldoutScore holdoutBefore, holdoutAfter;
    int holdoutSamplesPerPixel = 1;  // the held-out targets' supersampling, squared
    bool finite = true;              // every parameter of every group
    maps::MapEffects effects;
    std::vector<std::pair<std::string, int>> parameters;  // per group: name, count
    int tessLevel = 0;                                    // as rendered (a crack-free power of two)
    int cageVertices = 0, cageFaces = 0, patches = 0, referenceTriangles = 0;
    int cageCreases = 0, cageCorners = 0;  // OpenSubdiv tags: sharp edges, sharp vertices
    context::GlInfo gl;
    std::string glProvider;
    std::vector<gl::ProgramVariant> shaderVariants;  // every program the run compiled
    std::map<std::string, std::uintmax_t> exports;   // file name -> bytes
    std::string stopReason = "steps";                // steps, converged, no_gain or interrupted
    int bestStep = -1;                               // the step whose parameters were kept (plateau schedule)
    std::vector<MonitorMeasurement> monitored;       // the plateau schedule's, those before a resume included

    bool interrupted() const { return stopReason == "interrupted"; }
};

// report.json's keys: steps, steps_requested, resumed_from_step, interrupted, seconds,
// fit_seconds, loss_initial, loss_final and psnr_train[_initial] (where scored), psnr_holdout[_initial], finite,
// effects, parameters, renderer, gl_version, gl_provider, atomic_float, shader_variants,
// settings, cage, reference, exports, stop_reason, best_step, monitor_losses ([step, seconds of
// steps, loss] for each measurement of the plateau schedule's monitored loss).
nlohmann::json toJson(const FitReport& report);

// report.json's `reference`: its path, its triangles and, where the file can be read, its
// XXH3-128 digest (`xxh3_128`), by which a reader of the folder (the viewer) knows the file at
// that path is still the one the result was made from before it opens it.
nlohmann::json referenceJson(const std::filesystem::path& reference, int triangles);

}  // namespace subdfit::fit
