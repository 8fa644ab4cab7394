#include "simplify/simplify_job.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "fit/asset_export.h"
#include "fit/coded_refinement.h"
#include "fit/device_defaults.h"
#include "fit/state_blend.h"
#include "gl/buffer.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/input_file.h"
#include "io/output_folder.h"
#include "io/staged_folder.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "codec/subd_format.h"
#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/bake.h"
#include "simplify/compare/baselines.h"
#include "simplify/budget_search.h"
#include "simplify/candidate_choice.h"
#include "simplify/compare/comparison_image.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/simplify_plan.h"
#include "simplify/triangle_route.h"
#include "fit/image_metrics.h"
#include "surface/tessellation.h"
#include "util/error.h"
#include "util/warnings.h"
#include "util/interrupt.h"
#include "util/json_text.h"

namespace subdfit::simplify {
namespace {

// Baked maps are already close: the fit only refines them, with steps this much smaller than
// a fit from flat maps takes (each texel's estimate is noisy, and Adam's steps do not shrink
// with the signal).
constexpr float kRefineRate = 0.02f;
// The same for the cage's vertices: simplify's cages are limit-fitted to the reference, and on a
// dense one a full step (a sixth of an edge) tilts every normal under the estimator's noise.
constexpr float kRefineVertexRate = 1.0f / 30.0f;
// ... and with the noise gate (optim::GroupSettings::noiseGate): near such a start the gradient
// is mostly noise. From a poor start the gate only slows the first steps, so `fit` leaves it
// off (docs/optimizer.md).
constexpr float kRefineNoiseGate = 1.0f;

// What subdfit ships: asset.subd (cage and maps, codec/subd_format.h). asset.usdz, the map
// atlases and fitted.glb are conveniences for DCC tools and viewers, not what the budget counts.
nlohmann::json shippedFiles(const std::map<std::string, std::uintmax_t>& exports) {
    return {{"asset.subd", exports.at("asset.subd")}};
}

// The fitted cage as it ships: asset.subd decoded (its positions and maps at the bits they were
// coded with) drawn on the held-out views, and with a full comparison its surface distance.
Quality scoreCage(gl::ProgramCache& programs, fit::FitRun& run, const fit::FitReport& fitted,
                  const std::filesystem::path& out, const SimplifyOptions& o) {
    Quality ours;
    ours.files = shippedFiles(fitted.exports);
    ours.bytes = totalBytes(ours.files);
    ours.shipped = "asset.subd";
    // Drawn and measured with the fit's segments, as the bake route is (bakeBaseline).
    const int segments = run.fitter().renderer().tessLevel();
    const auto shipped = drawnAsFitted(programs, run.scene(), codec::readSubd(out / "asset.subd"), segments);
    setHoldout(fit::scoreHoldout(*shipped, run.scene().holdout), ours);
    if (o.compare >= CompareLevel::Full)
        ours.distance =
            shippedDistance(out / "asset.subd", segments, run.scene().frame, run.scene().reference, o.surfaceSamples);
    return ours;
}

// comparison.png: one held-out view of the reference, what shipped and each baseline.
void writeComparisonImage(const SimplifyReport& report, int resolution, const fit::FitScene& scene,
                          const std::filesystem::path& out) {
    std::vector<ComparisonColumn> columns{{"subdfit", &report.subdfit}};
    // A grown file's prefix is what the baselines, made at its budget, are weighed against.
    if (report.prefix && report.prefix->grown()) columns.push_back({"its prefix", &report.prefix->asset});
    if (report.cage) columns.push_back({"fitted cage", &*report.cage});
    for (const MadeBaseline& b : report.triangles) columns.push_back({b.title, &b.quality});
    if (report.bake) columns.push_back({"bake", &*report.bake});
    writeComparison(out / "comparison.png", resolution, scene.holdout.readColor(0), columns);
}

// The maps join the fit baked onto the cage as fitted so far (what the bake route would ship for
// this cage), then are only refined: the cage frozen (moving it would slide the maps off the
// detail they hold), the appearance at its full rate, the geometric maps slowed. Heights held
// back until the appearance had converged scored lower held out on every textured case
// measured (docs/measurements.md).
fit::MapStage mapStage(fit::FitRun& run) {
    return {.startFrom =
                [&run](const mesh::PolygonMesh& cage) {
                    return bakeFor(cage, run.scene().reference, *run.fitter().maps());
                },
            .freezeCage = true,
            .geometricRate = kRefineRate,
            .appearanceRate = 1.0f,
            .noiseGate = kRefineNoiseGate};
}

// Never a silent loss: an appearance on tiles carries the fitted colours and the reference's
// emission and occlusion, not its normal texture (that rides along only in its own atlas).
void warnOfWhatTilesLeaveOut(const std::filesystem::path& path, const mesh::PolygonMesh& reference, bool searched,
                             bool metallicRoughness) {
    const std::string lost = lostOnTiles(reference, metallicRoughness);
    if (lost.empty()) return;
    std::string why = atlasUnsuitability(reference);
    why = !why.empty() ? "no atlas: " + why : searched ? "the budget search chose them" : "no --appearance-atlas";
    warn(path.string() + ": the appearance is on per-face tiles (" + why + "), which do not carry its " + lost +
         " (the look may differ)");
}

// The appearance starts as the bake onto the starting cage: a grey surface against a coloured
// target would pull the cage where the colours differ, not the shape. A resumed run has its
// texels from the checkpoint, but an atlas's corner coordinates and the textures carried
// unfitted are not parameters: they come from the same bake.
void startAppearance(fit::FitRun& run, bool resumed) {
    maps::MapParameters* parameters = run.fitter().maps();
    if (!parameters || !parameters->effects().appearance()) return;
    const fit::FitScene& scene = run.scene();
    const surface::SurfaceMaps baked = bakeAppearance(scene.cage, scene.reference, appearanceBakeOf(*parameters));
    if (!resumed) run.startFrom(baked);
    else {
        if (baked.appearanceAtlas.present()) parameters->setAppearanceUvs(baked.appearanceAtlas.cornerUvs);
        parameters->setCarriedTextures(baked);
    }
}

// Simplify's cage starts limit-fitted: its vertices are refined with the smaller step and the
// gate. Past its first halving such a fit falls slowly, and longer windows would buy tenths of a
// dB for minutes (docs/optimizer.md): every window stays the full step's.
void refineGently(fit::FitRun& run) {
    fit::CageFitter& fitter = run.fitter();
    optim::ParameterGroup& vertices = fitter.vertexGroup();
    fitter.setRates(vertices, vertices.settings().epsilon, kRefineVertexRate * vertices.settings().learningRate);
    vertices.settings().noiseGate = kRefineNoiseGate;
    run.setWindowDoublings(0);
}

// The fit's stages, resumed from `checkpoint` when asked: the cage alone; the maps baked onto it;
// the maps refined on the frozen cage. Unlike `fit`, an interrupted simplify writes no results:
// they would cost the baselines' time after the user asked to stop, and the checkpoint keeps
// the steps taken.
void fitStages(fit::FitRun& run, const std::filesystem::path& checkpoint, bool resume, const fit::FitHooks& hooks) {
    const bool resumed = resume && run.resume(checkpoint);
    if (resume && !resumed && hooks.note)
        hooks.note("no checkpoint at " + checkpoint.string() + " to resume: starting from step 0");
    startAppearance(run, resumed);
    if (run.run(checkpoint, hooks, mapStage(run)) == fit::StopReason::Cancelled)
        throw Interrupted("interrupted at step " + std::to_string(run.step()) + " of " +
                          std::to_string(run.options().steps) + ", checkpointed in " + checkpoint.string());
}

// What one run works with, from the reference's load to its commit.
struct RunInputs {
    const SimplifyOptions& options;
    const fit::FitHooks& hooks;
    gl::ProgramCache& programs;
    fit::FitScene& scene;
    const mesh::PolygonMesh& reference;
    const context::GlContext& context;
    const std::filesystem::path& staged;
    BaselineSettings& baselines;
    SimplifyReport& report;
    std::optional<std::uintmax_t> grownTo = std::nullopt;  // --prefix: the whole file's budget
};

// The bytes a run aims at: --budget as given; without one (and without --faces), derived from
// the reference compressed.
struct TargetBudget {
    std::optional<std::uintmax_t> bytes;
    std::uintmax_t compressedReference = 0;  // 0 unless derived
};

TargetBudget targetBudget(const SimplifyOptions& options, const fit::FitScene& scene,
                          const std::filesystem::path& staged, const fit::FitHooks& hooks, StageSeconds& stages) {
    if (options.budget || options.faces) return {.bytes = options.budget};
    const std::uintmax_t compressed = compressedReferenceBytes(scene, staged / "reference.glb");
    const std::uintmax_t budget = defaultBudget(compressed);
    if (hooks.note)
        hooks.note("no --budget: " + std::to_string(budget) +
                   " bytes (the reference compressed: " + std::to_string(compressed) + ")");
    stages.lap("default_budget");
    return {.bytes = budget, .compressedReference = compressed};
}

// What is known before any fit: the triangle route at the budget (what a cage must beat), and
// either the route that ships without a cage tried or the cage's plan.
struct PreFit {
    TriangleBaselines triangles;
    std::optional<Route> route;
    std::optional<SimplifyPlan> plan;
};

PreFit decideBeforeFit(const SimplifyOptions& options, fit::FitOptions fitOptions, const TargetBudget& target,
                       gl::ProgramCache& programs, fit::FitScene& scene, const mesh::PolygonMesh& reference,
                       const BaselineSettings& baselines, const fit::FitHooks& hooks, StageSeconds& stages) {
    PreFit decided;
    const std::optional<std::uintmax_t>& budget = target.bytes;
    // The search's cages are CPU work: built from now on, beside the triangle route's.
    std::optional<CageLadder> cages;
    if (budget) cages.emplace(reference, budgetFaceCounts(options, *budget, scene), options.cageShape, prepareToJudge);
    if (budget) {
        decided.triangles = triangleBaselines(programs, scene, *budget, baselines, options.compare);
        stages.lap("triangle_route");
        if (options.route == RouteChoice::Auto)
            decided.route = routeBeforeFit(decided.triangles.best(), decided.triangles.holds, std::nullopt);
        if (decided.route) return decided;
    }
    try {
        // Where the route is ours to choose, a triangle route far ahead spares settling near ties.
        const double leastFitted =
            options.route == RouteChoice::Auto ? leastFittedMonitorPsnr(decided.triangles.best()) : -INFINITY;
        decided.plan = budget ? planWithinBudget(options, *budget, leastFitted, std::move(fitOptions), programs, scene,
                                                 reference, *cages, hooks.note)
                              : planByFaces(options, std::move(fitOptions), scene, reference);
    } catch (const NoCageFits& e) {
        // Never worse than the triangle route: where it fits and no cage does, it ships.
        if (options.route == RouteChoice::Auto) decided.route = routeWithoutCage(decided.triangles.best(), e.reason());
        if (!decided.route) throw;
        stages.lap("search");
        return decided;
    }
    stages.lap(budget ? "search" : "initial_cage");
    if (auto& planned = decided.plan->budget) {
        planned->derived = !options.budget;
        planned->compressedReference = target.compressedReference;
        if (options.route == RouteChoice::Auto)
            decided.route =
                routeBeforeFit(decided.triangles.best(), Holds::Part, fit::psnrFromLoss(planned->chosen.monitorLoss));
    }
    return decided;
}

// Writes the fitter's state as what ships, coded again with fewer map bits where the budget
// asks; whether it fits.
bool writeCoded(fit::FitRun& run, const SimplifyPlan& plan, const RunInputs& in) {
    SimplifyReport& report = in.report;
    report.fit = run.writeResults(in.staged, in.context);
    if (!report.budget) return true;
    std::uintmax_t& bytes = report.fit->exports.at("asset.subd");
    const std::uintmax_t budget = report.budget->bytes;
    report.budget->shipped = {
        .mapBits = plan.fit.mapBits, .appearanceQuality = plan.fit.appearanceQuality, .bytes = bytes};
    if (bytes <= budget) return true;
    report.budget->shipped = shipWithinBudget(run.shippable(), in.staged / "asset.subd", bytes, budget,
                                              plan.fit.mapBits, plan.fit.positionBits, plan.fit.appearanceQuality);
    bytes = report.budget->shipped.bytes;
    // The USD export follows asset.subd, coded again.
    const nlohmann::json usd = fit::exportUsd(plan.fit, in.staged);
    for (const auto& [name, usdBytes] : usd.items()) report.fit->exports[name] = usdBytes.get<std::uintmax_t>();
    return bytes <= budget;
}

// Whether the fitter's state, coded as writeCoded codes it, fits the budget; nothing written.
bool codesWithinBudget(fit::FitRun& run, const SimplifyPlan& plan, const RunInputs& in) {
    const std::uintmax_t budget = in.report.budget->bytes;
    const codec::SubdAsset asset = run.shippable();
    const std::uintmax_t bytes = codec::encodeSubd(asset, fit::subdPrecision(run.options())).size();
    return codeWithinBudget(asset, bytes, budget, plan.fit.mapBits, plan.fit.positionBits, plan.fit.appearanceQuality)
               .bytes <= budget;
}

// The loss on the choosing views of `asset` (drawn decoded, as it ships).
double choosingLoss(fit::FitRun& run, const RunInputs& in, const codec::SubdAsset& asset) {
    return fit::score(*drawnAsFitted(in.programs, run.scene(), asset), run.scene().choosing(in.programs)).loss;
}

// The fitted asset as written against its bake as the plan codes it (where the search judged
// it), both decoded, on the choosing views: at few map bits the coding can undo what the fit
// gained before it (docs/simplify.md, "Within the budget, as coded"). Leaves the fitter holding
// the one that ships; whether that is the fit.
bool fitLeadsAsCoded(fit::FitRun& run, const RunInputs& in, FitVerdict& verdict) {
    fit::CageFitter& fitter = run.fitter();
    const fit::CageFitter::State fitted = fitter.state();
    const surface::SurfaceMaps fittedMaps = fitter.surfaceMaps();
    verdict.shippedFittedLoss = choosingLoss(run, in, codec::readSubd(in.staged / "asset.subd"));
    holdTheBake(run);
    verdict.shippedBakedLoss = choosingLoss(run, in, codec::decodeSubd(run.coded(), "the bake"));
    if (verdict.shippedFittedLoss >= verdict.shippedBakedLoss) return false;
    fit::writeMaps(fitter, fittedMaps);
    fitter.restore(fitted);
    return true;
}

// A fitted asset over the budget: the most of the way from its bake to it (bisected) that codes
// within the budget, written, and false with the fitter holding the bake where none does.
bool pullWithinBudget(fit::FitRun& run, const SimplifyPlan& plan, const RunInputs& in) {
    fit::CageFitter& fitter = run.fitter();
    const fit::CageFitter::State fitted = fitter.state();
    const surface::SurfaceMaps fittedMaps = fitter.surfaceMaps();  // what θ does not hold
    holdTheBake(run);
    const fit::CageFitter::State baked = fitter.state();
    const auto hold = [&](float t) {
        fit::writeMaps(fitter, fittedMaps);
        fitter.restore(fit::between(baked, fitted, t));
    };
    const float t = fit::furthestThatHolds(
        [&](float t) {
            hold(t);
            return codesWithinBudget(run, plan, in);
        },
        fit::kBudgetBisections);
    if (t == 0.0f) {
        holdTheBake(run);
        return false;
    }
    hold(t);
    writeCoded(run, plan, in);
    in.report.fitVerdict->withinBudgetFraction = t;
    return true;
}

// Fitted heights are rougher than baked ones and code larger: where even the fewest bits leave
// the fitted asset over the budget, the most of the way to it from its bake that fits is weighed
// instead, and where none fits, its bake (weighed within the budget by the search) ships. What
// fits ships only where it leads its bake as both are coded.
void writeWithinBudget(fit::FitRun& run, const SimplifyPlan& plan, const RunInputs& in) {
    std::optional<FitVerdict>& verdict = in.report.fitVerdict;
    bool fits = writeCoded(run, plan, in);
    if (!verdict || !verdict->fitShips) return;
    const std::uintmax_t fittedBytes = in.report.budget ? in.report.budget->shipped.bytes : 0;
    if (!fits) {
        verdict->overBudgetBytes = fittedBytes;
        fits = pullWithinBudget(run, plan, in);
    }
    if (fits && fitLeadsAsCoded(run, in, *verdict)) {
        if (verdict->withinBudgetFraction < 1.0f && in.hooks.note) {
            char line[160];
            std::snprintf(line, sizeof line,
                          "the fitted asset codes to %ju bytes, over the budget: %.0f %% of the way to it from its "
                          "bake fits, and ships",
                          fittedBytes, 100.0 * verdict->withinBudgetFraction);
            in.hooks.note(line);
        }
        return;
    }
    if (!fits) holdTheBake(run);
    writeCoded(run, plan, in);
    verdict->fitShips = false;
    if (verdict->overBudgetBytes > 0 && verdict->withinBudgetFraction == 1.0f) {
        if (in.hooks.note)
            in.hooks.note("the fitted asset codes to " + std::to_string(verdict->overBudgetBytes) +
                          " bytes, over the budget, and no way to it from its bake fits: its bake ships");
        return;
    }
    if (in.hooks.note) {
        char line[160];
        std::snprintf(line, sizeof line,
                      "the fitted asset as coded loses to its bake (loss %.4g against %.4g): the bake ships",
                      verdict->shippedFittedLoss, verdict->shippedBakedLoss);
        in.hooks.note(line);
    }
}

// --coded-steps: the heights that ship refined as the decoder reads them (fit/coded_refinement.h):
// at a budget's few bits the rounding costs more than the fit gains. What ships is replaced where
// the refined heights, coded, fit the budget and draw closer on the choosing views; else the
// fitter holds what shipped again.
void refineAsCoded(fit::FitRun& run, const SimplifyPlan& plan, const RunInputs& in) {
    SimplifyReport& report = in.report;
    fit::CageFitter& fitter = run.fitter();
    if (in.options.codedSteps == 0 || !fitter.maps() || !fitter.maps()->displacement()) return;
    const fit::CageFitter::State shipped = fitter.state();
    const surface::SurfaceMaps shippedMaps = fitter.surfaceMaps();
    codec::SubdPrecision precision = fit::subdPrecision(plan.fit);
    if (report.budget) {
        precision.displacementBits = report.budget->shipped.mapBits;
        precision.appearanceQuality = report.budget->shipped.appearanceQuality;
    }
    const auto fits = [&](std::size_t bytes) { return !report.budget || bytes <= report.budget->bytes; };
    const auto withinBudget = [&] { return fits(codec::encodeSubd(run.shippable(), precision).size()); };
    const fit::CodedRefinement refined = fit::refineAsCoded(
        run, {.bits = precision.displacementBits, .steps = in.options.codedSteps},
        [&] { return fit::score(fitter, in.scene.choosing(in.programs)).loss; }, withinBudget);
    CodedFitReport& coded =
        report.codedFit.emplace(CodedFitReport{.refinement = refined, .bits = precision.displacementBits});
    if (refined.bestStep > 0) {
        const std::vector<unsigned char> file = codec::encodeSubd(run.shippable(), precision);
        coded.bytes = file.size();
        coded.shippedLoss = choosingLoss(run, in, codec::readSubd(in.staged / "asset.subd"));
        coded.refinedLoss = choosingLoss(run, in, codec::decodeSubd(file, "the refined heights"));
        coded.ships = fits(file.size()) && coded.refinedLoss < coded.shippedLoss;
    }
    if (!coded.ships) {
        fit::writeMaps(fitter, shippedMaps);
        fitter.restore(shipped);
    } else {
        writeCoded(run, plan, in);
    }
    if (in.hooks.note) {
        char line[200];
        std::snprintf(line, sizeof line, "the heights fitted as coded: %d steps (%.1f s), their lowest at step %d%s",
                      refined.steps, refined.seconds, refined.bestStep,
                      coded.ships ? ": they ship" : ": what was written ships");
        in.hooks.note(line);
    }
}

// --prefix: the asset shipped at the prefix's budget grown to the whole budget
// (simplify/prefix_growth.h) where it can and a grown file draws closer on the choosing views:
// asset.subd and its USD replaced, what shipped measured again.
void growToTheBudget(fit::FitRun& run, const SimplifyPlan& plan, const RunInputs& in, std::uintmax_t budget) {
    SimplifyReport& report = in.report;
    PrefixReport& prefix =
        report.prefix.emplace(PrefixReport{.budget = budget, .asset = report.subdfit, .growth = {}, .why = {}});
    const auto note = [&](const std::string& why) {
        prefix.why = why;
        if (in.hooks.note) in.hooks.note("the file does not grow past its prefix: " + why);
    };
    if (report.route.shipped != "cage") return note("a triangle mesh ships at the prefix's budget");
    const std::filesystem::path path = in.staged / "asset.subd";
    const std::string bytes = io::readInputFile(path);
    const std::span file{reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()};
    GrowingAsset asset = growingAsset(file, path.string(), 0);
    if (asset.asset.maps.hasDisplacement())
        asset.bits = report.budget ? report.budget->shipped.mapBits : plan.fit.mapBits;
    if (const std::string why = whyNotGrown(asset.asset); !why.empty()) return note(why);
    Growth growth = growWithinBudget(asset, mesh::triangulated(in.reference), budget, [&](const codec::SubdAsset& a) {
        try {
            return choosingLoss(run, in, a);
        } catch (const gl::StorageBlockExceeded&) {  // not drawable here: never chosen
            return std::numeric_limits<double>::infinity();
        }
    });
    if (growth.file.empty()) {
        note(growth.why);
        prefix.growth = std::move(growth);
        return;
    }
    io::writeTextAtomically(path, {reinterpret_cast<const char*>(growth.file.data()), growth.file.size()});
    report.fit->exports["asset.subd"] = growth.file.size();
    const nlohmann::json usd = fit::exportUsd(plan.fit, in.staged);
    for (const auto& [name, usdBytes] : usd.items()) report.fit->exports[name] = usdBytes.get<std::uintmax_t>();
    report.subdfit = scoreCage(in.programs, run, *report.fit, in.staged, in.options);
    if (in.hooks.note)
        in.hooks.note("grown to " + std::to_string(growth.file.size()) + " bytes (heights at T = " +
                      std::to_string(growth.chosen.resolution) + ", " + std::to_string(growth.chosen.bits) +
                      " bits): its first " + std::to_string(prefix.asset.bytes) + " bytes are the asset above");
    growth.file.clear();
    prefix.growth = std::move(growth);
}

// Fits the plan's cage, writes its results into the staging folder, and weighs it against the
// triangle route (made here at the cage's bytes when there is no budget): the better ships. With
// --compare full, the bake route too.
void fitAndWeigh(const RunInputs& in, SimplifyPlan& plan, TriangleBaselines& triangles,
                 std::optional<std::uintmax_t> budget) {
    const SimplifyOptions& options = in.options;
    SimplifyReport& report = in.report;
    StageSeconds& stages = report.stages;
    if (in.scene.shading != render::ShadingModel::Geometry && plan.fit.appearanceAtlas == 0)
        warnOfWhatTilesLeaveOut(options.fit.reference, in.reference, plan.budget.has_value(),
                                in.scene.shading == render::ShadingModel::MetallicRoughness);
    const mesh::PolygonMesh cage = in.scene.cageWorld;
    fit::FitRun run(fit::resolved(plan.fit), in.programs, in.scene, fit::ReportScores::HoldoutOnly);
    refineGently(run);
    // Each stage is judged on the views the verdict below reads.
    fit::FitHooks hooks = in.hooks;
    hooks.judge = [&] { return fit::score(run.fitter(), in.scene.choosing(in.programs)).loss; };
    fitStages(run, options.fit.out / "checkpoint.bin", options.fit.resume, hooks);
    report.fitVerdict = keepTheFitWhereItPays(run, in.programs);
    if (report.fitVerdict->fittedLoss > report.fitVerdict->bakedLoss && in.hooks.note) {
        char line[160];
        std::snprintf(
            line, sizeof line,
            "the fit did not improve on its bake on the choosing views (loss %.4g against %.4g): the bake ships",
            report.fitVerdict->fittedLoss, report.fitVerdict->bakedLoss);
        in.hooks.note(line);
    }
    stages.lap("fit");

    mesh::writeObj(in.staged / "initial_cage.obj", cage);
    writeWithinBudget(run, plan, in);
    stages.lap("exports");
    refineAsCoded(run, plan, in);
    stages.lap("coded_fit");
    report.subdfit = scoreCage(in.programs, run, *report.fit, in.staged, options);
    stages.lap("metrics");
    if (!budget) {
        triangles = triangleBaselines(in.programs, in.scene, report.subdfit.bytes, in.baselines, options.compare);
        stages.lap("triangle_route");
    }
    const TriangleChoice best = triangles.best();
    report.route =
        options.route == RouteChoice::Cage ? Route{.why = "--route cage"} : chooseRoute(report.subdfit, best, budget);
    if (report.route.shipped != "cage") {
        report.cage = report.subdfit;
        report.subdfit = shipTriangles(best, in.staged);
    }
    if (in.grownTo) {
        growToTheBudget(run, plan, in, *in.grownTo);
        stages.lap("growth");
    }
    if (options.compare >= CompareLevel::Full) {
        in.baselines.segments = run.fitter().renderer().tessLevel();
        // A fit that kept its bake ships the bake route's own file, already scored.
        const Quality& cage = report.cage ? *report.cage : report.subdfit;
        std::optional<ScoredFile> scored;
        if (std::filesystem::exists(in.staged / "asset.subd"))
            scored.emplace(in.staged / "asset.subd", cage, in.baselines.segments);
        report.bake = bakeBaseline(in.programs, in.scene, plan.bakeRoute, in.baselines, scored);
        if (plan.budget) report.bake->details["over_budget"] = report.bake->bytes > plan.budget->bytes;
        stages.lap("baseline_bake");
    }
}

nlohmann::json toJson(const CodedFitReport& c) {
    const fit::CodedRefinement& r = c.refinement;
    nlohmann::json out = {{"bits", c.bits},
                          {"steps", r.steps},
                          {"best_step", r.bestStep},
                          {"seconds", r.seconds},
                          {"start_loss", r.startLoss},
                          {"best_loss", r.bestLoss},
                          {"over_budget", r.overBudget},
                          {"ships", c.ships}};
    if (r.bestStep > 0) {
        out["bytes"] = c.bytes;
        out["shipped_choosing_loss"] = c.shippedLoss;
        out["refined_choosing_loss"] = c.refinedLoss;
    }
    return out;
}

nlohmann::json toJson(const PrefixReport& p) {
    nlohmann::json out = {{"bytes", p.asset.bytes}, {"psnr_holdout", p.asset.psnrHoldout}, {"budget", p.budget}};
    if (p.asset.distance) out["mean_distance"] = p.asset.distance->meanDistance;
    const auto candidate = [](const GrowthCandidate& c) {
        return nlohmann::json{
            {"resolution", c.resolution}, {"bits", c.bits}, {"bytes", c.bytes}, {"choosing_loss", c.loss}};
    };
    if (p.growth) {
        out["asset_choosing_loss"] = p.growth->assetLoss;
        nlohmann::json& weighed = out["grown_candidates"] = nlohmann::json::array();
        for (const GrowthCandidate& c : p.growth->candidates) weighed.push_back(candidate(c));
    }
    if (p.grown()) out["grown"] = candidate(p.growth->chosen);
    else out["why"] = p.why;
    return out;
}

}  // namespace

std::optional<double> unquantisedPsnr(const SimplifyReport& r) {
    // The fit's end is what ships before coding: where its bake won, the fitter holds the bake again.
    if (r.route.shipped != "cage" || !r.fit) return std::nullopt;
    return r.fit->holdoutAfter.psnr;
}

nlohmann::json toJson(const SimplifyReport& r) {
    nlohmann::json report = r.fit
                                ? fit::toJson(*r.fit)
                                : nlohmann::json{{"settings", r.settings},
                                                 {"reference", fit::referenceJson(r.reference, r.referenceTriangles)}};
    // What shipped (where the cage did, its held-out PSNR is the fit's, from the same views).
    nlohmann::json shipped = toJson(r.subdfit);
    shipped.erase("path");  // `route` names it
    report.update(shipped);
    if (const auto unquantised = unquantisedPsnr(r)) report["psnr_holdout_unquantised"] = *unquantised;
    report["seconds"] = r.seconds;
    report["seconds_by_stage"] = r.stages.toJson();

    // The routes and baselines were weighed at the prefix's budget, against what it holds.
    const Quality& weighedCage = r.cage ? *r.cage : r.prefix ? r.prefix->asset : r.subdfit;
    nlohmann::json route = toJson(r.route), weighed = nlohmann::json::object();
    auto weigh = [&](const std::string& name, const Quality& q) {
        weighed[name] = {{"psnr_holdout", q.psnrHoldout}, {"bytes", q.bytes}};
    };
    if (r.fit) weigh("cage", weighedCage);
    for (const MadeBaseline& b : r.triangles) weigh(b.name, b.quality);
    route["weighed"] = weighed;
    report["route"] = route;

    if (r.compare != CompareLevel::None) {
        nlohmann::json baselines = nlohmann::json::object(), margins = nlohmann::json::object();
        nlohmann::json columns = {"reference", "subdfit"};
        if (r.prefix && r.prefix->grown()) columns.push_back("prefix");
        auto add = [&](const std::string& name, const Quality* q) {
            if (!q) return;
            baselines[name] = toJson(*q);
            margins[name] = (r.prefix ? r.prefix->asset : r.subdfit).psnrHoldout - q->psnrHoldout;
            columns.push_back(name);
        };
        add("cage", r.cage ? &*r.cage : nullptr);
        for (const MadeBaseline& b : r.triangles) add(b.name, &b.quality);
        add("bake", r.bake ? &*r.bake : nullptr);
        for (const auto& [name, why] : r.unavailable) baselines[name] = {{"skipped", why}};
        report["baselines"] = baselines;
        report["margin_db"] = margins;
        report["comparison_columns"] = columns;
    }
    report["simplify"] = {{"faces_requested", r.facesRequested},
                          {"reference_triangles", r.referenceTriangles},
                          {"compare", nameOf(r.compare)},
                          {"budget", r.budgetBytes},
                          {"budget_derived", r.budgetDerived}};
    if (r.budget) report["budget"] = toJson(*r.budget);
    if (r.prefix) report["prefix"] = toJson(*r.prefix);
    if (r.codedFit) report["coded_fit"] = toJson(*r.codedFit);
    if (r.fitVerdict) {
        nlohmann::json& verdict = report["fit_verdict"] = {{"shipped", r.fitVerdict->fitShips ? "fit" : "bake"}};
        if (r.fitVerdict->fitMoved)
            verdict["choosing_loss"] = {{"fit", r.fitVerdict->fittedLoss}, {"bake", r.fitVerdict->bakedLoss}};
        else verdict["why"] = "the fit ended at its bake";
        if (r.fitVerdict->overBudgetBytes > 0) {
            const bool pulled = r.fitVerdict->withinBudgetFraction < 1.0f;
            verdict["why"] = "the fitted asset coded to " + std::to_string(r.fitVerdict->overBudgetBytes) +
                             " bytes, over the budget" +
                             (pulled ? "; the most of the way to it from the bake that fits was weighed instead" : "");
            verdict["over_budget_bytes"] = r.fitVerdict->overBudgetBytes;
            if (pulled) verdict["within_budget_fraction"] = r.fitVerdict->withinBudgetFraction;
        }
        if (r.fitVerdict->shippedBakedLoss > 0.0) {
            verdict["shipped_choosing_loss"] = {{"fit", r.fitVerdict->shippedFittedLoss},
                                                {"bake", r.fitVerdict->shippedBakedLoss}};
            if (!r.fitVerdict->fitShips) verdict["why"] = "the fitted asset as coded loses to its bake";
        }
    }
    return report;
}

namespace {

// The reference, refused where --appearance-atlas asks for what it cannot give.
mesh::PolygonMesh loadReference(const SimplifyOptions& options) {
    mesh::PolygonMesh reference = mesh::loadReference(options.fit.reference);
    if (options.fit.appearanceAtlas > 0)
        if (const std::string why = atlasUnsuitability(reference); !why.empty())
            throw OptionError("appearance_atlas", "needs a reference whose appearance is one textured material; " +
                                                      options.fit.reference.string() + ": " + why);
    return reference;
}

}  // namespace

SimplifyReport runSimplify(const SimplifyOptions& asked, const fit::FitHooks& hooks) {
    validate(asked);
    // With --prefix every choice is made at the prefix's budget; the file then grows to the budget.
    SimplifyOptions options = asked;
    if (asked.prefix) options.budget = std::exchange(options.prefix, std::nullopt);
    const std::filesystem::path& out = options.fit.out;
    io::checkOutputFolder(out, {.ownMarkers = fit::kFitResultMarkers, .force = options.fit.force});
    const auto started = std::chrono::steady_clock::now();
    SimplifyReport report;
    report.facesRequested = options.faces.value_or(0);
    report.compare = options.compare;
    report.reference = options.fit.reference;
    StageSeconds& stages = report.stages;
    const mesh::PolygonMesh reference = loadReference(options);

    auto context = context::createHeadlessContext(options.fit.glProvider);
    fit::FitOptions fitOptions = options.fit;
    const std::string chosen = fit::resolveForCurrentDevice(fitOptions);
    if (!chosen.empty() && hooks.note) hooks.note(chosen);
    gl::ProgramCache programs(gl::platformDefines());
    fitOptions.cage = out / "initial_cage.obj";  // where the report says the cage came from
    report.settings = fit::settingsJson(fitOptions);
    fit::FitScene scene(fit::resolved(fitOptions), programs, {}, reference);
    report.referenceTriangles = scene.reference.faceCount();
    stages.lap("load");

    // Every result lands in one commit, or none does.
    io::StagedFolder staged(out);
    BaselineSettings baselineSettings{.dir = staged.path() / "baselines",
                                      .compactMaps = fitOptions.compactMaps,
                                      .surfaceSamples = options.surfaceSamples,
                                      .distance = options.compare >= CompareLevel::Full};
    const TargetBudget target = targetBudget(options, scene, staged.path(), hooks, stages);
    report.budgetBytes = target.bytes.value_or(0);
    report.budgetDerived = target.bytes && !options.budget;
    PreFit decided = decideBeforeFit(options, std::move(fitOptions), target, programs, scene, reference,
                                     baselineSettings, hooks, stages);
    TriangleBaselines& triangles = decided.triangles;
    report.budget = decided.plan ? decided.plan->budget : std::nullopt;
    if (decided.route) {
        report.route = *decided.route;
        report.subdfit = shipTriangles(triangles.best(), staged.path());
        if (asked.prefix)
            report.prefix = {
                .budget = *asked.budget, .asset = report.subdfit, .growth = {}, .why = "a triangle mesh ships"};
    } else {
        fitAndWeigh({options, hooks, programs, scene, reference, *context, staged.path(), baselineSettings, report,
                     asked.prefix ? asked.budget : std::nullopt},
                    *decided.plan, triangles, target.bytes);
    }
    report.triangles = std::move(triangles.made);
    report.unavailable = std::move(triangles.unavailable);
    // Weighed by the route (report.json's route.weighed), not kept as baselines.
    if (options.compare == CompareLevel::None) std::filesystem::remove_all(baselineSettings.dir);
    if (options.compare >= CompareLevel::Full) {
        writeComparisonImage(report, options.fit.resolution > 0 ? options.fit.resolution : scene.holdout.resolution(),
                             scene, staged.path());
        stages.lap("comparison_image");
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (report.fit) report.fit->seconds = report.seconds;
    io::writeTextAtomically(staged.path() / "report.json", jsonText(toJson(report), 2));
    staged.commit();
    return report;
}

}  // namespace subdfit::simplify
