#include "simplify/simplify_job.h"

#include <chrono>

#include "fit/device_defaults.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/output_folder.h"
#include "io/staged_folder.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "export/subd_format.h"
#include "simplify/atlas_bake.h"
#include "simplify/bake.h"
#include "simplify/baselines.h"
#include "simplify/textured_baselines.h"
#include "simplify/budget_search.h"
#include "simplify/decimate.h"
#include "simplify/comparison_image.h"
#include "simplify/initial_cage.h"
#include "surface/tessellation.h"
#include "util/error.h"
#include "util/warnings.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

// Baked maps are already close: the fit only refines them, with steps this much smaller than
// a fit from flat maps takes (each texel's estimate is noisy, and Adam's steps do not shrink
// with the signal). Measured on Spot (300 faces, T = 4): 0.1 and 0.02 both end within 0.1 dB
// of the bake itself, 1 loses 5 dB to noise.
constexpr float kRefineRate = 0.02f;
// The same for the cage's vertices: simplify's cages are limit-fitted to the reference, and on a
// dense one a full step (a sixth of an edge) tilts every normal under the estimator's noise
// (the relief Spot's 8 000-face cage lost 9 dB held out in its first 10 steps).
constexpr float kRefineVertexRate = 1.0f / 30.0f;
// ... and with the noise gate (optim::GroupSettings::noiseGate): near such a start the gradient
// is mostly noise (docs/optimizer.md: at the refine step, a tenth of a dB lost in 10 steps with
// it, four times that without). From a poor start the gate only slows the first steps, so
// `fit` leaves it off.
constexpr float kRefineNoiseGate = 1.0f;

// What subdfit ships: asset.subd (cage and maps, export/subd_format.h). cage.glb, the map
// atlases and fitted.glb are conveniences for DCC tools and viewers, not what the budget counts.
nlohmann::json shippedFiles(const std::map<std::string, std::uintmax_t>& exports) {
    return {{"asset.subd", exports.at("asset.subd")}};
}

// The budget search's largest cage. A dense bare cage ships for ~2.2 bytes a face and its limit
// surface shades closer than heights on a coarse one (bunny, 17.4 KB: 8 000 bare faces 37.1 dB,
// 1 069 faces with T = 3 heights 34.8 dB; at 100 KB, 16 000 bare faces reach in 32 KB the
// 38.7 dB that 8 000 faces with T = 2 heights reached in 71 KB). Past subdiv::kDenseCageFaces a
// cage is drawn one isolation level shallower, a quarter of the triangles a step.
constexpr int kMostBudgetFaces = 16 * kDefaultFaces;
// Past this many faces the fit of a budget's cage takes proportionally fewer steps (unless
// --steps was given): the search's bake is already close (on the relief Spot and the bunny the
// fit of 2 000-8 000-face cages kept its start), and --budget should cost about what a
// 2 000-face fit does.
constexpr int kMostFullyFittedFaces = 2 * kDefaultFaces;

// The fitted maps code differently from the baked ones the budget search measured (and the
// search does not weigh the appearance maps): when the file comes out over, the appearance
// images get a lower JPEG quality, then the heights and normals fewer bits, until it fits.
// Returns {"map_bits", "appearance_quality"} as shipped.
nlohmann::json shipWithinBudget(const std::filesystem::path& subd, std::uintmax_t budget, int mapBits,
                                int appearanceQuality, fit::FitReport& fitted) {
    std::uintmax_t& bytes = fitted.exports.at("asset.subd");
    auto precision = exporter::SubdPrecision::forMapBits(mapBits, appearanceQuality);
    auto shipped = [&] {
        return nlohmann::json{{"map_bits", precision.displacementBits}, {"appearance_quality", precision.appearanceQuality}};
    };
    if (bytes <= budget) return shipped();
    const exporter::SubdAsset decoded = exporter::readSubd(subd);
    std::vector<std::pair<int, int>> ladder;  // (bits, quality), coarser and coarser
    // Quality in small steps: a JPEG's bytes fall ~5 % a step, and every byte left is detail lost.
    constexpr int kFewestBits = 6, kLowestQuality = 30, kQualityStep = 5;
    int quality = appearanceQuality;
    if (decoded.maps.hasBaseColor() || decoded.maps.hasMetallicRoughness())
        while (quality - kQualityStep >= kLowestQuality) ladder.emplace_back(mapBits, quality -= kQualityStep);
    for (int bits = mapBits - 1; bits >= kFewestBits; --bits) ladder.emplace_back(bits, quality);
    for (size_t k = 0; k < ladder.size(); ++k) {
        precision = exporter::SubdPrecision::forMapBits(ladder[k].first, ladder[k].second);
        const auto encoded =
            exporter::encodeSubd(exporter::shippableAsset(decoded.cage, decoded.maps, precision.positionBits), precision);
        if (encoded.size() <= budget || k + 1 == ladder.size()) {
            bytes = exporter::writeBytes(subd, encoded).bytes;
            if (bytes <= budget) break;
        }
    }
    return shipped();
}

// Scores the fitted scene and both baselines; writes cage.glb, baselines/ and comparison.png
// into `out`.
void evaluate(const SimplifyOptions& o, const std::filesystem::path& out, gl::ProgramCache& programs,
              const BakeRoute& bakeRoute, fit::FitRun& run, const fit::FitReport& fitted, SimplifyReport& report) {
    fit::CageFitter& fitter = run.fitter();
    fit::FitScene& scene = run.scene();
    mesh::PolygonMesh cage = scene.cage;
    cage.positions = fitter.vertices();
    mesh::PolygonMesh cageWorld = cage;
    cageWorld.positions = scene.frame.toWorld(cage.positions);
    const int segments = fitter.renderer().tessLevel();

    Quality& ours = report.subdfit;
    shipCage(out / "cage.glb", cageWorld, o.fit.draco);
    ours.files = shippedFiles(fitted.exports);
    ours.bytes = totalBytes(ours.files);
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        fitter.render(camera, target);
    }, ours);
    ours.distance = shippedDistance(out / "asset.subd", segments, scene.frame, scene.reference, o.surfaceSamples);

    const BaselineSettings settings{.dir = out / "baselines", .draco = o.fit.draco,
                                    .compactMaps = o.fit.compactMaps, .surfaceSamples = o.surfaceSamples, .segments = segments};
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
    report.bake = bakeBaseline(programs, scene, bakeRoute, settings);
    if (o.budget > 0) report.bake.details["over_budget"] = report.bake.bytes > o.budget;
    std::vector<const std::vector<glm::vec4>*> columns{&ours.view, &report.decimation.view};
    if (report.gltfpack) columns.push_back(&report.gltfpack->view);
    columns.push_back(&report.bake.view);
    writeComparison(out / "comparison.png", o.fit.resolution, scene.holdout.readColor(0), columns);
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
    // its gain (the Duck at 20 KB, 126 faces, T = 8: held-out 38.95 dB refining the colour alone,
    // 38.26 = the bake with the heights moving too); widenToHeights lets them in after.
    const bool appearance = parameters->effects().appearance();
    for (auto* g : parameters->groups()) {
        const bool appearanceGroup = g == parameters->baseColor() || g == parameters->metallicRoughness();
        if (appearance && !appearanceGroup) fitter.setOptimised(*g, false);
        fitter.setRates(*g, g->settings().epsilon, (appearanceGroup ? 1.0f : kRefineRate) * g->settings().learningRate);
        g->settings().noiseGate = kRefineNoiseGate;
    }
}

// Once the appearance has converged, the heights join it for the steps left: where the cage
// is too coarse for the reference's relief, the images move them past what the bake could (the
// relief Duck at 20 KB, 476 faces, T = 3: bake 29.56 dB, the colour alone 29.76, then the
// heights 30.83). The stage ends at its best state, so it never undoes the appearance's gain.
bool widenToHeights(fit::FitRun& run) {
    auto* parameters = run.fitter().maps();
    if (!parameters || !parameters->effects().appearance() || !parameters->displacement()) return false;
    run.fitter().setOptimised(*parameters->displacement(), true);
    return true;
}

// Where the fit starts: without a budget, the initial cage of --faces; with one, the budget
// search's choice (simplify/budget_search.h), whose maps, resolution and bits go into `o` and
// `fitOptions`, and whose best candidate with maps is the bake route at those bytes.
struct Start {
    nlohmann::json budget;              // the search's report, null without a budget
    std::optional<BakeRoute> bakeRoute;  // none: the initial cage with the run's maps
};

Start chooseStart(SimplifyOptions& o, fit::FitOptions& fitOptions, gl::ProgramCache& programs, fit::FitScene& scene,
                  const mesh::PolygonMesh& reference, bool stepsByDevice, const fit::FitHooks& hooks) {
    Start start;
    if (o.budget <= 0) {
        scene.setCage(initialCage(reference, {.faces = o.faces > 0 ? o.faces : kDefaultFaces}));
        return start;
    }
    const BudgetSearch search{.budget = o.budget,
                              .faceCounts = o.faces > 0 ? std::vector<int>{o.faces}
                                                        : faceCountsFor(o.budget, scene.reference.faceCount(), kMostBudgetFaces),
                              .allowedMaps = o.fit.maps,
                              .appearance = {.baseColor = scene.shading != render::ShadingModel::Geometry,
                                             .metallicRoughness = scene.shading == render::ShadingModel::MetallicRoughness},
                              .appearanceQualities = {o.fit.appearanceQuality},
                              .appearanceAtlases = o.fit.appearanceAtlas > 0 ? std::vector<int>{o.fit.appearanceAtlas}
                                                                              : atlasSizesFor(scene.reference)};
    if (hooks.note) hooks.note("budget " + std::to_string(o.budget) + " bytes: trying candidates");
    const auto searchStarted = std::chrono::steady_clock::now();
    const BudgetChoice choice = searchBudget(programs, scene, reference, search, hooks.note);
    fitOptions.maps = o.fit.maps = choice.chosen.maps;
    if (choice.chosen.appearanceResolution > 0 || choice.chosen.appearanceAtlas > 0) {
        if (choice.chosen.appearanceResolution > 0)
            fitOptions.appearanceResolution = o.fit.appearanceResolution = choice.chosen.appearanceResolution;
        fitOptions.appearanceAtlas = o.fit.appearanceAtlas = choice.chosen.appearanceAtlas;
        fitOptions.appearanceQuality = o.fit.appearanceQuality = choice.chosen.appearanceQuality;
    }
    if (choice.chosen.mapResolution > 0) {
        fitOptions.mapResolution = o.fit.mapResolution = choice.chosen.mapResolution;
        fitOptions.mapBits = o.fit.mapBits = choice.chosen.mapBits;
        fitOptions.shadingNormal = o.fit.shadingNormal = surface::toString(choice.chosen.shadingNormal);
        // The search judged this cage with maps baked onto it as it is: the fit refines that
        // (moving the cage first would leave what was judged; measured on the relief Spot at
        // 20 KB: 3.06e-3 mean distance after 400 cage steps and the bake on the fitted cage,
        // 2.36e-3 refining the judged bake, in half the time).
        fitOptions.mapsStart = o.fit.mapsStart = 0.0f;
    }
    if (const int faces = choice.cageWorld.faceCount(); stepsByDevice && faces > kMostFullyFittedFaces)
        fitOptions.steps = o.fit.steps = std::max(1, int(std::lround(double(o.fit.steps) * kMostFullyFittedFaces / faces)));
    scene.setCage(choice.cageWorld);
    start.budget = toJson(choice, o.budget);
    start.budget["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - searchStarted).count();
    // The bake route at these bytes: the search's best candidate with maps, as it is; when none
    // fits, the chosen cage with the cheapest maps the search tries (reported over budget), not
    // the default maps at many times the bytes.
    if (choice.bestWithMaps || search.allowedMaps.geometric()) {
        const BudgetCandidate route = choice.bestWithMaps ? *choice.bestWithMaps
                                                          : BudgetCandidate{.maps = search.allowedMaps,
                                                                            .mapResolution = search.mapResolutions.front(),
                                                                            .mapBits = search.mapBits.front()};
        mesh::PolygonMesh bakeCage = choice.bestWithMaps ? choice.bestWithMapsCage : choice.cageWorld;
        bakeCage.positions = scene.frame.toNormalized(bakeCage.positions);
        const bool appearance = route.appearanceResolution > 0 || route.appearanceAtlas > 0;
        start.bakeRoute = BakeRoute{.cage = std::move(bakeCage), .effects = route.maps, .resolution = route.mapResolution,
                                    .bits = route.mapBits,
                                    .appearanceResolution = appearance ? route.appearanceResolution : o.fit.appearanceResolution,
                                    .appearanceQuality = appearance ? route.appearanceQuality : o.fit.appearanceQuality,
                                    .appearanceAtlas = appearance ? route.appearanceAtlas : o.fit.appearanceAtlas,
                                    .shadingNormal = route.shadingNormal};
    }
    return start;
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

}  // namespace

void validate(const SimplifyOptions& o) {
    if (o.faces != 0 && (o.faces < 4 || o.faces > 1000000))
        throw OptionError("faces", "must be in 4..1000000, got " + std::to_string(o.faces));
    if (o.budget != 0 && o.budget < 100) throw OptionError("budget", "must be at least 100 bytes");
    if (o.surfaceSamples < 1000) throw OptionError("surface_samples", "must be >= 1000");
    if (o.fit.appearanceAtlas > 0 && o.fit.maps.normalMap)
        throw OptionError("appearance_atlas", "takes heights alone (--maps displacement): the atlas's texture coordinates "
                                              "leave the shipped glTF no room for a normal map on tiles");
    fit::validate(o.fit);
}

nlohmann::json settingsJson(const SimplifyOptions& o) {
    nlohmann::json settings = fit::settingsJson(o.fit);
    settings["faces"] = o.faces;
    settings["budget"] = o.budget;
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
    if (!r.budget.is_null()) {
        report["budget"] = r.budget;
        report["budget"]["over_budget"] = r.subdfit.bytes > r.budget["bytes"].get<std::uintmax_t>();
    }
    return report;
}

SimplifyReport runSimplify(const SimplifyOptions& options, const fit::FitHooks& hooks) {
    validate(options);
    io::checkOutputFolder(options.fit.out, {.ownMarkers = fit::kFitResultMarkers, .force = options.fit.force});
    const auto started = std::chrono::steady_clock::now();
    SimplifyOptions o = options;
    const mesh::PolygonMesh reference = mesh::loadReference(o.fit.reference);
    if (o.fit.appearanceAtlas > 0)
        if (const std::string why = atlasUnsuitability(reference); !why.empty())
            throw OptionError("appearance_atlas", "needs a reference whose appearance is one textured material; " +
                                                      o.fit.reference.string() + ": " + why);

    auto context = context::createHeadlessContext(o.fit.glProvider);
    const std::string chosen = fit::resolveForCurrentDevice(o.fit);
    if (!chosen.empty() && hooks.note) hooks.note(chosen);
    gl::ProgramCache programs(gl::platformDefines());
    fit::FitOptions fitOptions = o.fit;
    fitOptions.cage = o.fit.out / "initial_cage.obj";  // where the report says the cage came from
    fit::FitScene scene(fitOptions, programs, {}, reference);
    const Start start = chooseStart(o, fitOptions, programs, scene, reference, options.fit.steps == fit::kByDevice, hooks);
    if (scene.shading != render::ShadingModel::Geometry && fitOptions.appearanceAtlas == 0)
        warnOfWhatTilesLeaveOut(o.fit.reference, reference, o.budget > 0,
                                scene.shading == render::ShadingModel::MetallicRoughness);
    const mesh::PolygonMesh cage = scene.cageWorld;
    fit::FitRun run(fitOptions, programs, scene);
    auto& vertices = run.fitter().vertexGroup();
    run.fitter().setRates(vertices, vertices.settings().epsilon, kRefineVertexRate * vertices.settings().learningRate);
    vertices.settings().noiseGate = kRefineNoiseGate;
    const auto checkpoint = o.fit.out / "checkpoint.bin";
    const bool resumed = o.fit.resume && run.resume(checkpoint);
    if (o.fit.resume && !resumed && hooks.note)
        hooks.note("no checkpoint at " + checkpoint.string() + " to resume: starting from step 0");
    // The appearance starts as the bake onto the starting cage: a grey surface against a
    // coloured target would pull the cage where the colours differ, not the shape.
    // A resumed run has its texels from the checkpoint, but an atlas's corner coordinates and
    // the textures carried unfitted are not parameters: they come from the same bake.
    if (maps::MapParameters* parameters = run.fitter().maps(); parameters && parameters->effects().appearance()) {
        const surface::SurfaceMaps baked = bakeAppearance(scene.cage, scene.reference, appearanceBakeOf(*parameters));
        if (!resumed) run.startFrom(baked);
        else {
            if (baked.appearanceAtlas.present()) parameters->setAppearanceUvs(baked.appearanceAtlas.cornerUvs);
            parameters->setCarriedTextures(baked);
        }
    }

    // Stages: the cage alone; the maps baked onto it; the maps refined on the frozen cage.
    // Unlike `fit`, an interrupted simplify writes no results: they would cost the baselines'
    // time after the user asked to stop, and the checkpoint keeps the steps taken.
    auto interrupted = [&] {
        return Interrupted("interrupted at step " + std::to_string(run.step()) + " of " + std::to_string(o.fit.steps) +
                           ", checkpointed in " + checkpoint.string());
    };
    if (run.run(checkpoint, hooks, [&](bool fresh) { startMaps(run, fresh); }, [&] { return widenToHeights(run); }) ==
        fit::StopReason::Cancelled)
        throw interrupted();

    // Every result lands in one commit, or none does.
    io::StagedFolder staged(o.fit.out);
    mesh::writeObj(staged.path() / "initial_cage.obj", cage);
    SimplifyReport report{.fit = run.writeResults(staged.path(), *context), .gltfpack = std::nullopt, .facesRequested = o.faces,
                          .budget = start.budget};
    if (o.budget > 0) report.budget.update(shipWithinBudget(staged.path() / "asset.subd", o.budget, o.fit.mapBits,
                                                                  o.fit.appearanceQuality, report.fit));
    const BakeRoute bakeRoute = start.bakeRoute ? *start.bakeRoute
                                                : BakeRoute{.cage = scene.cage, .effects = o.fit.maps,
                                                            .resolution = o.fit.mapResolution, .bits = o.fit.mapBits,
                                                            .appearanceResolution = o.fit.appearanceResolution,
                                                            .appearanceQuality = o.fit.appearanceQuality,
                                                            .appearanceAtlas = o.fit.appearanceAtlas,
                                                            .shadingNormal = surface::shadingNormalNamed(o.fit.shadingNormal)};
    evaluate(o, staged.path(), programs, bakeRoute, run, report.fit, report);
    report.fit.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io::writeTextAtomically(staged.path() / "report.json", toJson(report).dump(2) + "\n");
    staged.commit();
    return report;
}

}  // namespace subdfit::simplify
