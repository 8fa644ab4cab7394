#pragma once
// `subdfit simplify`: a dense asset in, a light Catmull-Clark cage and maps out, judged against
// the baselines a technical artist would otherwise use, at the same byte budget.
//
// DIR gets what `subdfit fit` writes (cage.obj, asset.subd, asset.usdz, maps, fitted.glb,
// report.json, PNGs) plus initial_cage.obj, comparison.png (held-out view: reference |
// subdfit | decimation | bake, error heat maps below) and baselines/ (each baseline's shipped
// files). report.json adds `bytes`, `chamfer`, `hausdorff` and `baselines`.
#include <optional>

#include <nlohmann/json.hpp>

#include "fit/coded_refinement.h"
#include "fit/fit_job.h"
#include "simplify/budget_search.h"
#include "simplify/fit_verdict.h"
#include "simplify/prefix_growth.h"
#include "simplify/compare/quality.h"
#include "simplify/route.h"
#include "simplify/simplify_options.h"
#include "simplify/stage_seconds.h"

namespace subdfit::simplify {

// With --prefix: the asset the file's first bytes are (what the prefix's budget shipped; the
// routes and baselines were weighed at it), and how its heights grew to the whole budget.
struct PrefixReport {
    std::uintmax_t budget = 0;     // the whole file's (--budget)
    Quality asset;                 // the file's first bytes, as they decode alone
    std::optional<Growth> growth;  // the grown files weighed (Growth::file not kept)
    std::string why;               // where the file did not grow
    bool grown() const { return growth && growth->chosen.resolution > 0; }
};

// The heights' fit on what the decoder reads (fit/coded_refinement.h), after what ships was
// written: whether its heights, coded, fit the budget and draw closer on the choosing views.
struct CodedFitReport {
    fit::CodedRefinement refinement;
    int bits = 0;                                 // of the heights
    std::uintmax_t bytes = 0;                     // the refined file's (0: none, nothing lowered the loss)
    double shippedLoss = 0.0, refinedLoss = 0.0;  // both decoded, on the choosing views
    bool ships = false;
};

// What a simplify did: the route it shipped, the fit's report when a cage was fitted, and what
// shipped and each baseline measured the same way at the same byte budget.
struct SimplifyReport {
    nlohmann::json settings;            // fit::settingsJson of the run's options
    std::optional<fit::FitReport> fit;  // none when a triangle route shipped before any fit
    Route route;
    Quality subdfit{};            // what shipped: the fitted cage, or the triangle route
    std::optional<Quality> cage;  // the fitted cage, where a triangle route shipped after its fit
    // The baselines: the triangle ones at the budget (decimation first), and the bake route;
    // which are made is --compare's to say.
    std::vector<MadeBaseline> triangles;
    std::vector<std::pair<std::string, std::string>> unavailable;  // asked for, not made here: name, why
    std::optional<Quality> bake;
    int facesRequested = 0;
    std::optional<FitVerdict> fitVerdict;    // where a cage was fitted
    std::optional<BudgetReport> budget;      // the search and what shipped, with a budget
    std::optional<PrefixReport> prefix;      // with --prefix
    std::optional<CodedFitReport> codedFit;  // with --coded-steps and heights
    std::uintmax_t budgetBytes = 0;  // the budget the routes were weighed at (0: the cage's bytes, --faces alone)
    bool budgetDerived = false;      // from the reference (route.h's defaultBudget)
    CompareLevel compare = CompareLevel::Full;
    std::filesystem::path reference;
    int referenceTriangles = 0;
    StageSeconds stages;
    double seconds = 0.0;  // the whole run
};

// The shipped cage and maps as fitted, before coding (the fit's end, or its bake where that won):
// what they would draw unquantised, held out. None where no cage shipped.
std::optional<double> unquantisedPsnr(const SimplifyReport& report);

// report.json: the fit's keys (when one ran); what shipped: `route` (shipped, path, why, and the
// held-out PSNR and bytes of each route weighed), bytes / files / psnr_holdout / ssim_holdout /
// chamfer / hausdorff / mean_distance; `baselines` (each with the `path` of its shipped file in
// DIR; the fitted cage among them where it did not ship) and `margin_db` (the shipped held-out
// PSNR minus each baseline's), unless --compare none; `simplify`; `seconds_by_stage`; and with a
// budget, `budget` (its bytes, whether derived, the candidates tried, the one chosen, `over_budget`);
// with --prefix, `prefix` (its bytes and held-out PSNR, the budget grown to, the grown files
// weighed and the one that shipped, or why none did: the margins are then the prefix's);
// where a cage was fitted, `fit_verdict` (whether the fit or its bake shipped, and their losses);
// where one shipped, `psnr_holdout_unquantised` (unquantisedPsnr: what the coding cost).
nlohmann::json toJson(const SimplifyReport& report);

// Checks DIR (io::checkOutputFolder), loads, chooses the route (route.h), fits a cage where one
// may win with DIR/checkpoint.bin as its checkpoint
// (resumed with options.fit.resume), and writes every result through DIR/.staging-PID/ in one
// commit. Throws subdfit::Error for bad options or inputs before anything is written, and
// Interrupted (no results, the checkpoint kept) when hooks.cancel or a stop request ends the fit.
SimplifyReport runSimplify(const SimplifyOptions& options, const fit::FitHooks& hooks = {});

}  // namespace subdfit::simplify
