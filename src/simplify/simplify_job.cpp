#include "simplify/simplify_job.h"

#include <chrono>

#include "fit/asset_export.h"
#include "fit/device_defaults.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/output_folder.h"
#include "io/staged_folder.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "export/subd_format.h"
#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/bake.h"
#include "simplify/compare/baselines.h"
#include "simplify/compare/textured_baselines.h"
#include "simplify/budget_search.h"
#include "simplify/cage/decimate.h"
#include "simplify/compare/comparison_image.h"
#include "simplify/cage/initial_cage.h"
#include "surface/tessellation.h"
#include "util/error.h"
#include "util/warnings.h"
#include "util/interrupt.h"

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

// What subdfit ships: asset.subd (cage and maps, export/subd_format.h). asset.usdz, the map
// atlases and fitted.glb are conveniences for DCC tools and viewers, not what the budget counts.
nlohmann::json shippedFiles(const std::map<std::string, std::uintmax_t>& exports) {
    return {{"asset.subd", exports.at("asset.subd")}};
}

// The budget search's largest cage: a dense bare cage ships cheaply, and its limit surface can
// shade closer than heights on a coarse one, so the search must be able to reach one. Past
// subdiv::kDenseCageFaces a cage is drawn one isolation level shallower, which keeps it affordable.
constexpr int kMostBudgetFaces = 16 * kDefaultFaces;
// Past this many faces the fit of a budget's cage takes proportionally fewer steps (unless
// --steps was given): the search's bake of a dense cage is already close, and --budget should
// cost about what a fit of this many faces does.
constexpr int kMostFullyFittedFaces = 2 * kDefaultFaces;

// The run decided before it starts, once: the options the fit runs with (with --budget, the
// search's choice in them), the bake route it is compared with, and the search's report.
struct SimplifyPlan {
    fit::FitOptions fit;
    BakeRoute bakeRoute;
    std::optional<BudgetReport> budget;
};

// Scores the fitted scene and the baselines; writes baselines/ and comparison.png into `out`.
void evaluate(const SimplifyOptions& o, const SimplifyPlan& plan, const std::filesystem::path& out,
              gl::ProgramCache& programs, fit::FitRun& run, SimplifyReport& report) {
    fit::CageFitter& fitter = run.fitter();
    fit::FitScene& scene = run.scene();
    const int segments = fitter.renderer().tessLevel();

    Quality& ours = report.subdfit;
    ours.files = shippedFiles(report.fit.exports);
    ours.bytes = totalBytes(ours.files);
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        fitter.render(camera, target);
    }, ours);
    ours.distance = shippedDistance(out / "asset.subd", segments, scene.frame, scene.reference, o.surfaceSamples);

    const BaselineSettings settings{.dir = out / "baselines", .compactMaps = plan.fit.compactMaps,
                                    .surfaceSamples = o.surfaceSamples, .segments = segments};
    std::filesystem::create_directories(settings.dir);
    // A material (textured or a plain colour) the triangle baselines must keep, as a user's would.
    if (scene.shading != render::ShadingModel::Geometry && scene.reference.materials) {
        report.decimation = texturedDecimationBaseline(programs, scene, ours.bytes, settings);
        report.gltfpack = texturedGltfpackBaseline(programs, scene, ours.bytes, settings);
    } else {
        const mesh::PolygonMesh welded = weldedTriangles(scene.reference);
        report.decimation = decimationBaseline(programs, scene, welded, ours.bytes, settings);
        report.gltfpack = gltfpackBaseline(programs, scene, welded, ours.bytes, settings);
    }
    report.bake = bakeBaseline(programs, scene, plan.bakeRoute, settings);
    if (plan.budget) report.bake.details["over_budget"] = report.bake.bytes > plan.budget->bytes;
    std::vector<ComparisonColumn> columns{{"subdfit", &ours}, {"decimation + Draco", &report.decimation}};
    if (report.gltfpack) columns.push_back({"gltfpack", &*report.gltfpack});
    columns.push_back({"bake", &report.bake});
    writeComparison(out / "comparison.png", plan.fit.resolution, scene.holdout.readColor(0), columns);
}

// How `parameters`' appearance is baked: its lattice, or its atlas.
AppearanceBakeOptions appearanceBakeOf(const maps::MapParameters& parameters) {
    return {.effects = parameters.effects(), .resolution = parameters.appearanceLayout().resolution,
            .atlas = parameters.appearanceAtlas().size};
}

// Every map `parameters` has, baked onto `cage` (normalised frame) from the reference.
surface::SurfaceMaps bakeEverything(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                    const maps::MapParameters& parameters) {
    const maps::MapEffects effects = parameters.effects();
    surface::SurfaceMaps maps;
    if (effects.geometric())
        maps = bakeMaps(cage, reference, {.effects = effects, .resolution = parameters.layout().resolution});
    if (effects.appearance()) {
        maps.setAppearance(bakeAppearance(cage, reference, appearanceBakeOf(parameters)));
    }
    return maps;
}

// The maps join the fit at `bakeStep`: baked onto the cage as fitted so far (what the bake route
// would ship for this cage), then only refined, with the cage frozen. A run resumed past that
// step has the maps from its checkpoint (`baked` false) but must freeze and slow them again.
void startMaps(fit::FitRun& run, bool bake) {
    fit::CageFitter& fitter = run.fitter();
    auto* parameters = fitter.maps();
    if (bake) {
        mesh::PolygonMesh current = run.scene().cage;
        current.positions = fitter.vertices();
        fit::writeMaps(fitter, bakeEverything(current, run.scene().reference, *parameters));
    }
    // The bake fits this cage: moving it now would slide the maps off the detail they hold.
    fitter.setOptimised(fitter.vertexGroup(), false);
    // With an appearance, the fit refines it alone first: heights that move beside it can undo
    // its gain; widenToHeights lets them in after.
    const bool appearance = parameters->effects().appearance();
    for (auto* g : parameters->groups()) {
        const bool appearanceGroup = g == parameters->baseColor() || g == parameters->metallicRoughness();
        if (appearance && !appearanceGroup) fitter.setOptimised(*g, false);
        fitter.setRates(*g, g->settings().epsilon, (appearanceGroup ? 1.0f : kRefineRate) * g->settings().learningRate);
        g->settings().noiseGate = kRefineNoiseGate;
    }
}

// Once the appearance has converged, the heights join it for the steps left: where the cage
// is too coarse for the reference's relief, the images move them past what the bake could. The
// stage ends at its best state, so it never undoes the appearance's gain.
bool widenToHeights(fit::FitRun& run) {
    auto* parameters = run.fitter().maps();
    if (!parameters || !parameters->effects().appearance() || !parameters->displacement()) return false;
    run.fitter().setOptimised(*parameters->displacement(), true);
    return true;
}

// The bake route of a cage (normalised frame) with the run's own maps.
BakeRoute bakeRouteOf(const mesh::PolygonMesh& cage, const fit::FitOptions& fit) {
    return {.cage = cage, .effects = fit.maps, .resolution = fit.mapResolution, .bits = fit.mapBits,
            .appearanceResolution = fit.appearanceResolution, .appearanceQuality = fit.appearanceQuality,
            .appearanceAtlas = fit.appearanceAtlas, .shadingNormal = fit.shadingNormal};
}

// Without a budget the fit starts from the initial cage of --faces, with the options as given.
SimplifyPlan planByFaces(const SimplifyOptions& o, fit::FitOptions fitOptions, fit::FitScene& scene,
                         const mesh::PolygonMesh& reference) {
    scene.setCage(initialCage(reference, {.faces = o.faces > 0 ? o.faces : kDefaultFaces}));
    BakeRoute route = bakeRouteOf(scene.cage, fitOptions);
    return {.fit = std::move(fitOptions), .bakeRoute = std::move(route), .budget = std::nullopt};
}

// What the budget search tries for `o` on `scene`.
BudgetSearch budgetSearchFor(const SimplifyOptions& o, std::uintmax_t budget, const fit::FitScene& scene) {
    return {.budget = budget,
            .faceCounts = o.faces > 0 ? std::vector<int>{o.faces}
                                      : faceCountsFor(budget, scene.reference.faceCount(), kMostBudgetFaces),
            .allowedMaps = o.fit.maps,
            .appearance = {.baseColor = scene.shading != render::ShadingModel::Geometry,
                           .metallicRoughness = scene.shading == render::ShadingModel::MetallicRoughness},
            .appearanceQualities = {o.fit.appearanceQuality},
            .appearanceAtlases = o.fit.appearanceAtlas > 0 ? std::vector<int>{o.fit.appearanceAtlas}
                                                          : atlasSizesFor(scene.reference)};
}

// The search's choice into the fit's options: its maps, their resolution, bits and shading
// normal, its appearance; and for a dense cage fewer steps, unless --steps was given.
void applyChoice(const BudgetCandidate& chosen, int cageFaces, bool stepsByDevice, fit::FitOptions& fit) {
    fit.maps = chosen.maps;
    if (chosen.appearanceResolution > 0 || chosen.appearanceAtlas > 0) {
        if (chosen.appearanceResolution > 0) fit.appearanceResolution = chosen.appearanceResolution;
        fit.appearanceAtlas = chosen.appearanceAtlas;
        fit.appearanceQuality = chosen.appearanceQuality;
    }
    if (chosen.mapResolution > 0) {
        fit.mapResolution = chosen.mapResolution;
        fit.mapBits = chosen.mapBits;
        fit.shadingNormal = chosen.shadingNormal;
        // The search judged this cage with maps baked onto it as it is: the fit refines that
        // from the start (moving the cage first would leave what was judged).
        fit.mapsStart = 0.0f;
    }
    if (stepsByDevice && cageFaces > kMostFullyFittedFaces)
        fit.steps = std::max(1, int(std::lround(double(fit.steps) * kMostFullyFittedFaces / cageFaces)));
}

// The bake route at the budget's bytes: the search's best candidate with maps, as it is; when
// none fits, the chosen cage with the cheapest maps the search tries (reported over budget),
// not the default maps at many times the bytes; with no maps allowed, the chosen cage with the
// run's own.
BakeRoute budgetBakeRoute(const BudgetChoice& choice, const BudgetSearch& search, const fit::FitOptions& fit,
                          const fit::FitScene& scene) {
    if (!choice.bestWithMaps && !search.allowedMaps.geometric()) return bakeRouteOf(scene.cage, fit);
    const BudgetCandidate route = choice.bestWithMaps ? *choice.bestWithMaps
                                                      : BudgetCandidate{.maps = search.allowedMaps,
                                                                        .mapResolution = search.mapResolutions.front(),
                                                                        .mapBits = search.mapBits.front()};
    mesh::PolygonMesh cage = choice.bestWithMaps ? choice.bestWithMapsCage : choice.cageWorld;
    cage.positions = scene.frame.toNormalized(cage.positions);
    const bool appearance = route.appearanceResolution > 0 || route.appearanceAtlas > 0;
    return {.cage = std::move(cage), .effects = route.maps, .resolution = route.mapResolution, .bits = route.mapBits,
            .appearanceResolution = appearance ? route.appearanceResolution : fit.appearanceResolution,
            .appearanceQuality = appearance ? route.appearanceQuality : fit.appearanceQuality,
            .appearanceAtlas = appearance ? route.appearanceAtlas : fit.appearanceAtlas,
            .shadingNormal = route.shadingNormal};
}

// With a budget the fit starts from the search's choice (simplify/budget_search.h).
SimplifyPlan planWithinBudget(const SimplifyOptions& o, std::uintmax_t budget, fit::FitOptions fitOptions,
                              gl::ProgramCache& programs, fit::FitScene& scene, const mesh::PolygonMesh& reference,
                              const fit::FitHooks& hooks) {
    const BudgetSearch search = budgetSearchFor(o, budget, scene);
    if (hooks.note) hooks.note("budget " + std::to_string(budget) + " bytes: trying candidates");
    const auto searchStarted = std::chrono::steady_clock::now();
    BudgetChoice choice = searchBudget(programs, scene, reference, search, hooks.note);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - searchStarted).count();
    applyChoice(choice.chosen, choice.cageWorld.faceCount(), o.fit.steps == fit::kByDevice, fitOptions);
    scene.setCage(choice.cageWorld);
    BakeRoute route = budgetBakeRoute(choice, search, fitOptions, scene);
    return {.fit = std::move(fitOptions),
            .bakeRoute = std::move(route),
            .budget = BudgetReport{.bytes = budget, .chosen = choice.chosen, .tried = std::move(choice.tried), .seconds = seconds,
                                   .shipped = {}}};
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

// The fit's stages, resumed from `checkpoint` when asked: the cage alone; the maps baked onto it;
// the maps refined on the frozen cage. Unlike `fit`, an interrupted simplify writes no results:
// they would cost the baselines' time after the user asked to stop, and the checkpoint keeps
// the steps taken.
// Simplify's cage starts limit-fitted: its vertices are refined with the smaller step and the gate.
void refineGently(fit::CageFitter& fitter) {
    optim::ParameterGroup& vertices = fitter.vertexGroup();
    fitter.setRates(vertices, vertices.settings().epsilon, kRefineVertexRate * vertices.settings().learningRate);
    vertices.settings().noiseGate = kRefineNoiseGate;
}

void fitStages(fit::FitRun& run, const std::filesystem::path& checkpoint, bool resume, const fit::FitHooks& hooks) {
    const bool resumed = resume && run.resume(checkpoint);
    if (resume && !resumed && hooks.note)
        hooks.note("no checkpoint at " + checkpoint.string() + " to resume: starting from step 0");
    startAppearance(run, resumed);
    if (run.run(checkpoint, hooks, [&](bool fresh) { startMaps(run, fresh); }, [&] { return widenToHeights(run); }) ==
        fit::StopReason::Cancelled)
        throw Interrupted("interrupted at step " + std::to_string(run.step()) + " of " +
                          std::to_string(run.options().steps) + ", checkpointed in " + checkpoint.string());
}

}  // namespace

void validate(const SimplifyOptions& o) {
    if (o.faces != 0 && (o.faces < 4 || o.faces > 1000000))
        throw OptionError("faces", "must be in 4..1000000, got " + std::to_string(o.faces));
    if (o.budget && *o.budget < 100) throw OptionError("budget", "must be at least 100 bytes");
    if (o.surfaceSamples < 1000) throw OptionError("surface_samples", "must be >= 1000");
    if (o.fit.appearanceAtlas > 0 && o.fit.maps.normalMap)
        throw OptionError("appearance_atlas", "takes heights alone (--maps displacement): the atlas's texture coordinates "
                                              "leave the shipped glTF no room for a normal map on tiles");
    fit::validate(o.fit);
}

nlohmann::json settingsJson(const SimplifyOptions& o) {
    nlohmann::json settings = fit::settingsJson(o.fit);
    settings["faces"] = o.faces;
    settings["budget"] = o.budget.value_or(0);  // 0: none, as a batch asset's identity hashes it
    settings["surface_samples"] = o.surfaceSamples;
    return settings;
}

nlohmann::json toJson(const SimplifyReport& r) {
    nlohmann::json report = fit::toJson(r.fit);
    nlohmann::json ours = toJson(r.subdfit);
    ours.erase("psnr_holdout");  // the fit's report has it already, from the same views
    report.update(ours);
    report["baselines"] = {{"decimation", toJson(r.decimation)}, {"bake", toJson(r.bake)}};
    report["margin_db"] = {{"decimation", r.subdfit.psnrHoldout - r.decimation.psnrHoldout},
                           {"bake", r.subdfit.psnrHoldout - r.bake.psnrHoldout}};
    report["comparison_columns"] = {"reference", "subdfit", "decimation", "bake"};
    if (r.gltfpack) {
        report["baselines"]["gltfpack"] = toJson(*r.gltfpack);
        report["margin_db"]["gltfpack"] = r.subdfit.psnrHoldout - r.gltfpack->psnrHoldout;
        report["comparison_columns"] = {"reference", "subdfit", "decimation", "gltfpack", "bake"};
    } else {
        report["baselines"]["gltfpack"] = {{"skipped", "gltfpack is not on PATH (Debian: apt-get install gltfpack)"}};
    }
    report["simplify"] = {{"faces_requested", r.facesRequested}, {"reference_triangles", r.fit.referenceTriangles}};
    if (r.budget) report["budget"] = toJson(*r.budget);
    return report;
}

SimplifyReport runSimplify(const SimplifyOptions& options, const fit::FitHooks& hooks) {
    validate(options);
    const std::filesystem::path& out = options.fit.out;
    io::checkOutputFolder(out, {.ownMarkers = fit::kFitResultMarkers, .force = options.fit.force});
    const auto started = std::chrono::steady_clock::now();
    const mesh::PolygonMesh reference = mesh::loadReference(options.fit.reference);
    if (options.fit.appearanceAtlas > 0)
        if (const std::string why = atlasUnsuitability(reference); !why.empty())
            throw OptionError("appearance_atlas", "needs a reference whose appearance is one textured material; " +
                                                      options.fit.reference.string() + ": " + why);

    auto context = context::createHeadlessContext(options.fit.glProvider);
    fit::FitOptions fitOptions = options.fit;
    const std::string chosen = fit::resolveForCurrentDevice(fitOptions);
    if (!chosen.empty() && hooks.note) hooks.note(chosen);
    gl::ProgramCache programs(gl::platformDefines());
    fitOptions.cage = out / "initial_cage.obj";  // where the report says the cage came from
    fit::FitScene scene(fitOptions, programs, {}, reference);
    const SimplifyPlan plan =
        options.budget ? planWithinBudget(options, *options.budget, std::move(fitOptions), programs, scene, reference, hooks)
                       : planByFaces(options, std::move(fitOptions), scene, reference);
    if (scene.shading != render::ShadingModel::Geometry && plan.fit.appearanceAtlas == 0)
        warnOfWhatTilesLeaveOut(options.fit.reference, reference, plan.budget.has_value(),
                                scene.shading == render::ShadingModel::MetallicRoughness);
    const mesh::PolygonMesh cage = scene.cageWorld;
    fit::FitRun run(plan.fit, programs, scene);
    refineGently(run.fitter());
    fitStages(run, out / "checkpoint.bin", options.fit.resume, hooks);

    // Every result lands in one commit, or none does.
    io::StagedFolder staged(out);
    mesh::writeObj(staged.path() / "initial_cage.obj", cage);
    SimplifyReport report{.fit = run.writeResults(staged.path(), *context), .gltfpack = std::nullopt,
                          .facesRequested = options.faces, .budget = plan.budget};
    if (report.budget) {
        std::uintmax_t& bytes = report.fit.exports.at("asset.subd");
        report.budget->shipped = shipWithinBudget(staged.path() / "asset.subd", bytes, report.budget->bytes,
                                                  plan.fit.mapBits, plan.fit.appearanceQuality);
        bytes = report.budget->shipped.bytes;
        // The USD export follows asset.subd, which may have been coded again.
        const nlohmann::json usd = fit::exportUsd(plan.fit, staged.path());
        for (const auto& [name, usdBytes] : usd.items()) report.fit.exports[name] = usdBytes.get<std::uintmax_t>();
    }
    evaluate(options, plan, staged.path(), programs, run, report);
    report.fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io::writeTextAtomically(staged.path() / "report.json", toJson(report).dump(2) + "\n");
    staged.commit();
    return report;
}

}  // namespace subdfit::simplify
