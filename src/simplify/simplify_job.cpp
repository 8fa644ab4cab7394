#include "simplify/simplify_job.h"

#include <chrono>

#include "gl/platform_defines.h"
#include "io/output_folder.h"
#include "io/staged_folder.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "simplify/bake.h"
#include "simplify/baselines.h"
#include "simplify/comparison_image.h"
#include "simplify/initial_cage.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

// Baked maps are already close: the fit only refines them, with steps this much smaller than
// a fit from flat maps takes (each texel's estimate is noisy, and Adam's steps do not shrink
// with the signal). Measured on Spot (300 faces, T = 4): 0.1 and 0.02 both end within 0.1 dB
// of the bake itself, 1 loses 5 dB to noise.
constexpr float kRefineRate = 0.02f;

exporter::FittedMaps fittedMaps(fit::CageFitter& fitter, const mesh::PolygonMesh& cage) {
    exporter::FittedMaps maps;
    if (auto* parameters = fitter.maps()) {
        maps.layout = parameters->layout();
        if (auto* g = parameters->displacement()) maps.displacement = g->read();
        if (auto* g = parameters->normalMap()) maps.normal = g->read();
    } else {
        maps.layout = maps::buildTexelLayout(cage, 1);
    }
    return maps;
}

// subdfit's shipped files: the cage GLB and the map files (fitted.glb is a convenience preview
// of the same asset for viewers without subdivision, not part of what the budget counts).
nlohmann::json shippedFiles(const nlohmann::json& exports, const nlohmann::json& cageFile) {
    nlohmann::json files = cageFile;
    for (const auto& [name, bytes] : exports.items())
        if (name != "fitted.glb") files[name] = bytes;
    return files;
}

// Evaluates the fitted scene and both baselines; writes cage.glb, baselines/ and comparison.png.
nlohmann::json evaluate(const SimplifyOptions& o, gl::ProgramCache& programs, const mesh::PolygonMesh& initialCage,
                        fit::CageFitter& fitter, fit::FitScene& scene, const nlohmann::json& exports) {
    const auto& out = o.fit.out;
    mesh::PolygonMesh fitted = scene.cage;
    fitted.positions = fitter.vertices();
    mesh::PolygonMesh fittedWorld = fitted;
    fittedWorld.positions = scene.frame.toWorld(fitted.positions);
    const int segments = fitter.renderer().tessLevel();

    Quality ours;
    ours.files = shippedFiles(exports, shipCage(out / "cage.glb", fittedWorld, o.fit.draco));
    ours.bytes = totalBytes(ours.files);
    scoreHoldout(scene.holdout, [&](const render::Camera& camera, const render::RenderTarget& target) {
        fitter.render(camera, target);
    }, ours);
    ours.distance = worldDistance(limitSurfaceTriangles(fitted, fittedMaps(fitter, fitted), segments),
                                  scene.reference, scene.frame, o.surfaceSamples);

    const BaselineSettings settings{.dir = out / "baselines", .draco = o.fit.draco,
                                    .compactMaps = o.fit.compactMaps, .surfaceSamples = o.surfaceSamples, .segments = segments};
    std::filesystem::create_directories(settings.dir);
    const Quality decimation = decimationBaseline(programs, scene, ours.bytes, settings);
    const Quality bake = bakeBaseline(programs, scene, initialCage, maps::parseMapEffects(o.fit.maps),
                                      o.fit.mapResolution, settings);
    writeComparison(out / "comparison.png", o.fit.resolution, scene.holdout.readColor(0),
                    {&ours.view, &decimation.view, &bake.view});

    nlohmann::json report = toJson(ours);
    report.erase("psnr_holdout");  // the fit's own report has it already, from the same views
    report["baselines"] = {{"decimation", toJson(decimation)}, {"bake", toJson(bake)}};
    report["margin_db"] = {{"decimation", ours.psnrHoldout - decimation.psnrHoldout},
                           {"bake", ours.psnrHoldout - bake.psnrHoldout}};
    report["comparison_columns"] = {"reference", "subdfit", "decimation", "bake"};
    return report;
}

}  // namespace

void validate(const SimplifyOptions& o) {
    if (o.faces < 4 || o.faces > 1000000)
        throw Error("invalid option: --faces must be in 4..1000000, got " + std::to_string(o.faces));
    if (o.surfaceSamples < 1000) throw Error("invalid option: surface samples must be >= 1000");
    fit::validate(o.fit);
}

nlohmann::json settingsJson(const SimplifyOptions& o) {
    nlohmann::json settings = fit::settingsJson(o.fit);
    settings["faces"] = o.faces;
    settings["surface_samples"] = o.surfaceSamples;
    return settings;
}

nlohmann::json runSimplify(const SimplifyOptions& options, const fit::FitHooks& hooks) {
    validate(options);
    io::checkOutputFolder(options.fit.out, {.ownMarkers = fit::kFitResultMarkers, .force = options.fit.force});
    const auto started = std::chrono::steady_clock::now();
    SimplifyOptions o = options;
    const mesh::PolygonMesh reference = mesh::loadMesh(o.fit.reference);
    const mesh::PolygonMesh cage = initialCage(reference, {.faces = o.faces});

    auto context = context::createHeadlessContext(o.fit.glProvider);
    gl::ProgramCache programs(gl::platformDefines());
    fit::FitScene scene(o.fit, programs, cage, reference);
    fit::CageFitter fitter(programs, scene.cage, fit::fitSettings(o.fit));

    fit::FitHooks withBake = hooks;
    // Coarse to fine: the maps start from a bake onto the cage as fitted so far (what the bake
    // route would ship for this cage), and the fit only refines them from there.
    withBake.onMapsStart = [&](fit::CageFitter& fitter, fit::FitScene& fitted, bool restored) {
        auto* parameters = fitter.maps();
        if (!restored) {
            mesh::PolygonMesh current = fitted.cage;
            current.positions = fitter.vertices();
            const auto baked = bakeMaps(current, fitted.reference,
                                        {.effects = parameters->effects(), .resolution = parameters->layout().resolution});
            if (auto* g = parameters->displacement()) g->write(baked.displacement);
            if (auto* g = parameters->normalMap()) g->write(baked.normal);
        }
        // The bake fits this cage: moving it now would slide the maps off the detail they hold.
        fitter.setOptimised(fitter.vertexGroup(), false);
        for (auto* g : parameters->groups()) fitter.setRates(*g, g->settings().epsilon, kRefineRate * fitter.baseLearningRate(*g));
    };
    const auto checkpoint = o.fit.out / "checkpoint.bin";
    fit::FitHistory history = fit::fitSteps(o.fit, scene, fitter, checkpoint, withBake);
    // Unlike `fit`, an interrupted simplify writes no results: they would cost the baselines'
    // time after the user asked to stop, and the checkpoint keeps the steps taken.
    if (history.interrupted(o.fit))
        throw Interrupted("interrupted at step " + std::to_string(history.steps) + " of " + std::to_string(o.fit.steps) +
                          ", checkpointed in " + checkpoint.string());

    // Every result lands in one commit, or none does.
    io::StagedFolder staged(o.fit.out);
    fit::FitOptions results = o.fit;
    results.out = staged.path();
    results.cage = o.fit.out / "initial_cage.obj";
    mesh::writeObj(staged.path() / "initial_cage.obj", cage);
    history.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    SimplifyOptions stagedOptions = o;
    stagedOptions.fit = results;
    auto report = fit::writeFitResults(results, programs, *context, scene, fitter, history,
                                       [&](fit::CageFitter& fitted, fit::FitScene& fittedScene, const nlohmann::json& exports) {
        auto extra = evaluate(stagedOptions, programs, scene.cage, fitted, fittedScene, exports);
        extra["simplify"] = {{"faces_requested", o.faces}, {"reference_triangles", fittedScene.reference.faceCount()}};
        return extra;
    });
    staged.commit();
    return report;
}

}  // namespace subdfit::simplify
