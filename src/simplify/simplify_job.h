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

#include "fit/fit_job.h"
#include "simplify/budget_search.h"
#include "simplify/compare/quality.h"

namespace subdfit::simplify {

// What `simplify` changes of a fit's defaults: a displacement map (shading normals come from its
// derivatives: in every budget search so far a normal map cost more than it gave), at a
// resolution a light asset can afford, shipped compact; and the cage fitted alone for most of
// the run, since the maps are baked onto it and only refined (see simplify_job.cpp).
inline fit::FitOptions simplifyFitDefaults() {
    fit::FitOptions o;
    o.maps = {.displacement = true};
    o.mapResolution = 4;
    o.mapsStart = 0.8f;
    o.compactMaps = true;
    return o;
}

struct SimplifyOptions {
    fit::FitOptions fit = simplifyFitDefaults();  // fit.reference: the dense asset; fit.cage is set by simplify
    int faces = 0;                // triangles of the cage; 0: kDefaultFaces, or chosen by the budget
    std::optional<std::uintmax_t> budget;  // bytes asset.subd may take; simplify/budget_search.h
    int surfaceSamples = 100000;  // per side, for Chamfer and Hausdorff
};

inline constexpr int kDefaultFaces = 1000;

// Throws subdfit::Error ("invalid option: ...") before any work.
void validate(const SimplifyOptions& options);

// The fit's settings and simplify's own (see fit::settingsJson); `budget` 0 without one.
nlohmann::json settingsJson(const SimplifyOptions& options);

// What a simplify did: the fit's report, and subdfit's asset and each baseline measured the
// same way at the same byte budget.
struct SimplifyReport {
    fit::FitReport fit;
    Quality subdfit{}, decimation{}, bake{};
    std::optional<Quality> gltfpack;  // none when gltfpack is not installed
    int facesRequested = 0;
    std::optional<BudgetReport> budget;  // the search and what shipped, with --budget
};

// report.json: the fit's keys, subdfit's bytes / files / chamfer / hausdorff / mean_distance,
// `baselines` (each with the `path` of its shipped file in DIR), `margin_db` (subdfit's held-out PSNR minus each baseline's), `simplify` and, with
// a budget, `budget` (its bytes, the candidates tried, the one chosen, `over_budget`).
nlohmann::json toJson(const SimplifyReport& report);

// Checks DIR (io::checkOutputFolder), loads, fits with DIR/checkpoint.bin as its checkpoint
// (resumed with options.fit.resume), and writes every result through DIR/.staging-PID/ in one
// commit. Throws subdfit::Error for bad options or inputs before anything is written, and
// Interrupted (no results, the checkpoint kept) when hooks.cancel or a stop request ends the fit.
SimplifyReport runSimplify(const SimplifyOptions& options, const fit::FitHooks& hooks = {});

}  // namespace subdfit::simplify
