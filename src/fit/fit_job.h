#pragma once
// `subdfit fit`: load a cage and a reference, render targets, fit the cage's control vertices
// (and maps), write cage.obj, the exports, report.json and before/after/target images of a
// held-out view into a folder.
#include <atomic>
#include <functional>

#include <nlohmann/json.hpp>

#include "fit/fit_options.h"

namespace subdfit::fit {

struct Progress {
    int step, steps;
    float loss;
    double seconds, etaSeconds;
};

using ProgressSink = std::function<void(const Progress&)>;

// Throws subdfit::Error for bad options or inputs before anything is written. `cancel`, when
// set during the fit, stops it early and still writes the results of the steps taken.
nlohmann::json runFit(const FitOptions& options, const ProgressSink& progress = {},
                      const std::atomic<bool>* cancel = nullptr);

}  // namespace subdfit::fit
