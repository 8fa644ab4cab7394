#pragma once
// The run `simplify` decides before its fit, once: the options the fit runs with (with a budget,
// the search's choice in them), the bake route it is compared with, and the search's report. The
// fit, the baselines and report.json then read the plan; nothing is decided twice.
#include <cstdint>
#include <optional>

#include <functional>
#include <string>

#include "fit/fit_scene.h"
#include "simplify/budget_search.h"
#include "simplify/compare/baselines.h"
#include "simplify/simplify_options.h"

namespace subdfit::simplify {

struct SimplifyPlan {
    fit::FitOptions fit;
    BakeRoute bakeRoute;
    std::optional<BudgetReport> budget;
};

// Without a budget the fit starts from the initial cage of --faces, with the options as given.
SimplifyPlan planByFaces(const SimplifyOptions& options, fit::FitOptions fitOptions, fit::FitScene& scene,
                         const mesh::PolygonMesh& reference);

// The face counts of the cages the budget search tries at `budget`: a CageLadder of them can be
// started before the search (it builds them on a thread of its own).
std::vector<int> budgetFaceCounts(const SimplifyOptions& options, std::uintmax_t budget, const fit::FitScene& scene);

// With a budget the fit starts from the search's choice (simplify/budget_search.h), among the
// cages of `cages` (a ladder of budgetFaceCounts()); `say` reports its candidates. Below
// `leastFittedMonitorPsnr` no candidate is fitted (BudgetSearch).
SimplifyPlan planWithinBudget(const SimplifyOptions& options, std::uintmax_t budget, double leastFittedMonitorPsnr,
                              fit::FitOptions fitOptions, gl::ProgramCache& programs, fit::FitScene& scene,
                              const mesh::PolygonMesh& reference, CageLadder& cages,
                              const std::function<void(const std::string&)>& say);

}  // namespace subdfit::simplify
