#pragma once
// `subdfit fit`: check the output folder, load a cage and a reference, render targets, fit the
// cage's control vertices (and maps) with a FitRun, and write cage.obj, the exports,
// report.json and before / after / target images of a held-out view into a folder.
#include <string>
#include <vector>

#include "fit/fit_run.h"

namespace subdfit::fit {

// What a folder of fit results holds, so that a later run may write there again
// (io::checkOutputFolder).
inline const std::vector<std::string> kFitResultMarkers = {"report.json", "checkpoint.bin"};

// Interrupted (hooks.cancel), it still writes the results of the steps taken. Throws
// subdfit::Error for bad options or inputs before anything is written.
FitReport runFit(const FitOptions& options, const FitHooks& hooks = {});

}  // namespace subdfit::fit
