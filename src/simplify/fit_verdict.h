#pragma once
// Whether a fit earned its steps: the fitted state against the bake it started from.
#include <cstdint>

#include "fit/fit_run.h"
#include "gl/program_cache.h"

namespace subdfit::simplify {

struct FitVerdict {
    bool fitShips = true;
    bool fitMoved = true;                      // false: the fit ended at its bake (no losses measured)
    double fittedLoss = 0.0, bakedLoss = 0.0;  // on the choosing views
    std::uintmax_t overBudgetBytes = 0;        // > 0: the fit won there, but its asset came to this, over the budget
    // < 1: the fitted asset being over the budget, what was weighed in its place is this fraction of
    // the way to it from the bake (the most that codes within the budget).
    float withinBudgetFraction = 1.0f;
    // Both as asset.subd holds them (decoded, on the choosing views), where the fit won before
    // coding and its asset fits: few map bits can undo what the fit gained. 0: not weighed.
    double shippedFittedLoss = 0.0, shippedBakedLoss = 0.0;
};

// Leaves in `run`'s fitter whichever of its fitted state and its bake (the scene's initial cage,
// every map baked onto it: bakeFor) has the lower loss on the choosing views
// (fit::FitScene::choosing), the bake where they tie, and says which.
FitVerdict keepTheFitWhereItPays(fit::FitRun& run, gl::ProgramCache& programs);

// Puts the bake in `run`'s fitter (where the fitted asset codes larger than the budget allows,
// while its bake was weighed within it).
void holdTheBake(fit::FitRun& run);

}  // namespace subdfit::simplify
