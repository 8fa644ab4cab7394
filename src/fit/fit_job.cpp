#include "fit/fit_job.h"

#include <chrono>
#include <cmath>

#include "fit/asset_export.h"
#include "fit/checkpoint.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/output_folder.h"
#include "mesh/obj_writer.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// Every parameter of every group, maps included.
bool allFinite(CageFitter& fitter) {
    for (auto* group : fitter.groups())
        for (float value : group->read())
            if (!std::isfinite(value)) return false;
    return true;
}

nlohmann::json effectsJson(const maps::MapEffects& effects) {
    auto list = nlohmann::json::array({"subdivision"});
    if (effects.displacement) list.push_back("displacement");
    if (effects.normalMap) list.push_back("normal_map");
    return list;
}

nlohmann::json parametersJson(CageFitter& fitter) {
    nlohmann::json counts = nlohmann::json::object();
    for (auto* group : fitter.groups()) counts[group->name()] = group->count();
    return counts;
}

nlohmann::json variantsJson(const gl::ProgramCache& programs) {
    auto list = nlohmann::json::array();
    for (const auto& variant : programs.variants()) {
        nlohmann::json defines = nlohmann::json::object();
        for (const auto& [name, value] : variant.defines) defines[name] = value;
        list.push_back({{"name", variant.name}, {"files", variant.files}, {"defines", defines}});
    }
    return list;
}

std::vector<glm::vec4> renderHoldout(CageFitter& fitter, const FitScene& scene) {
    render::RenderTarget image(scene.holdout.resolution(), scene.holdout.resolution());
    fitter.render(scene.holdout.camera(0), image);
    return image.readColor();
}

}  // namespace

nlohmann::json runFit(const FitOptions& o, const FitHooks& hooks) {
    validate(o);
    io::checkOutputFolder(o.out, {.ownMarkers = kFitResultMarkers, .force = o.force});
    auto context = context::createHeadlessContext(o.glProvider);
    gl::ProgramCache programs(gl::platformDefines());
    FitScene scene(o, programs);
    return runFit(o, programs, *context, scene, hooks);
}

nlohmann::json runFit(const FitOptions& o, gl::ProgramCache& programs, const context::GlContext& context,
                      FitScene& scene, const FitHooks& hooks) {
    validate(o);
    const auto started = Clock::now();
    CageFitter fitter(programs, scene.cage, fitSettings(o));
    FitHistory history = fitSteps(o, scene, fitter, o.out / "checkpoint.bin", hooks);
    history.seconds = secondsSince(started);
    return writeFitResults(o, programs, context, scene, fitter, history, hooks.evaluate);
}

FitHistory fitSteps(const FitOptions& o, FitScene& scene, CageFitter& fitter, const std::filesystem::path& checkpoint,
                    const FitHooks& hooks) {
    const auto started = Clock::now();
    FitHistory history;
    history.beforeImage = renderHoldout(fitter, scene);
    history.trainBefore = score(fitter, scene.training);
    history.holdoutBefore = score(fitter, scene.holdout);

    const std::string runFingerprint = checkpointFingerprint(o, scene.cage, scene.reference);
    if (o.resume) {
        if (const auto saved = readCheckpoint(checkpoint, runFingerprint)) {
            try {
                fitter.restore(*saved);
            } catch (const Error& e) {
                throw fileError(checkpoint.string(), e.what());
            }
            history.firstStep = std::min(saved->steps, o.steps);
        } else if (hooks.note) {
            hooks.note("no checkpoint at " + checkpoint.string() + " to resume: starting from step 0");
        }
    }
    auto saveCheckpoint = [&] {
        std::filesystem::create_directories(checkpoint.parent_path());
        writeCheckpoint(checkpoint, runFingerprint, fitter.state());
    };

    const auto fitStarted = Clock::now();
    const int reportEvery = std::max(1, o.steps / 50);
    int step = history.firstStep;
    for (; step < o.steps; ++step) {
        if (hooks.cancel && hooks.cancel->load()) break;
        if (hooks.onMapsStart && fitter.maps()) {
            const int start = fitter.mapsStartStep();
            if (step == start || (step == history.firstStep && step > start)) hooks.onMapsStart(fitter, scene, step > start);
        }
        // The loss is only read for progress, so about eight steps per report measure it.
        const bool measureLoss = step % std::max(1, reportEvery / 8) == 0;
        const auto views = viewsForStep(o, step);
        for (int sample = 0; sample < o.samplesPerStep; ++sample) fitter.accumulate(scene.training, views, measureLoss);
        fitter.update();
        if (hooks.progress && ((step + 1) % reportEvery == 0 || step + 1 == o.steps)) {
            const double seconds = secondsSince(fitStarted);
            const double done = double(step + 1 - history.firstStep);
            hooks.progress({step + 1, o.steps, fitter.takeMeanLoss(), seconds, seconds / done * double(o.steps - step - 1)});
        }
        if ((step + 1) % o.checkpointEvery == 0) saveCheckpoint();
    }
    saveCheckpoint();
    history.steps = step;
    history.fitSeconds = secondsSince(fitStarted);
    history.seconds = secondsSince(started);
    return history;
}

nlohmann::json writeFitResults(const FitOptions& o, gl::ProgramCache& programs, const context::GlContext& context,
                               FitScene& scene, CageFitter& fitter, const FitHistory& history,
                               const FitEvaluation& evaluate) {
    const auto afterImage = renderHoldout(fitter, scene);
    const ViewSetScore trainAfter = score(fitter, scene.training);
    const ViewSetScore holdoutAfter = score(fitter, scene.holdout);
    const auto glInfo = context::currentGlInfo();
    const auto effects = fitter.maps() ? fitter.maps()->effects() : maps::MapEffects{};

    nlohmann::json report = {
        {"steps", history.steps},
        {"steps_requested", o.steps},
        {"resumed_from_step", history.firstStep},
        {"interrupted", history.steps < o.steps},
        {"seconds", history.seconds},
        {"fit_seconds", history.fitSeconds},
        {"loss_initial", history.trainBefore.loss},
        {"loss_final", trainAfter.loss},
        {"psnr_train_initial", history.trainBefore.psnr},
        {"psnr_train", trainAfter.psnr},
        {"psnr_holdout_initial", history.holdoutBefore.psnr},
        {"psnr_holdout", holdoutAfter.psnr},
        {"finite", allFinite(fitter)},
        {"effects", effectsJson(effects)},
        {"parameters", parametersJson(fitter)},
        {"renderer", glInfo.renderer},
        {"gl_version", glInfo.version},
        {"gl_provider", context.providerName()},
        {"atomic_float", glInfo.hasAtomicFloat},
        {"shader_variants", variantsJson(programs)},
        {"settings", settingsJson(o)},
        {"cage", {{"path", o.cage.string()}, {"vertices", scene.cage.vertexCount()}, {"faces", scene.cage.faceCount()},
                  {"patches", fitter.renderer().patchCount()}}},
        {"reference", {{"path", o.reference.string()}, {"triangles", scene.reference.faceCount()}}},
    };

    report["settings"]["tess_level"] = fitter.renderer().tessLevel();  // as rendered: a power of two

    // Outputs only now that everything has worked; each file appears whole or not at all.
    std::filesystem::create_directories(o.out);
    mesh::PolygonMesh fittedWorld = scene.cageWorld;
    fittedWorld.positions = scene.frame.toWorld(fitter.vertices());
    mesh::writeObj(o.out / "cage.obj", fittedWorld);
    report["exports"] = exportAsset(o, fitter, scene.frame, fittedWorld);
    if (evaluate) report.update(evaluate(fitter, scene, report["exports"]));
    const int res = o.resolution;
    if (!history.beforeImage.empty()) io::writeImage(o.out / "before.png", history.beforeImage, res, res);
    io::writeImage(o.out / "after.png", afterImage, res, res);
    io::writeImage(o.out / "target.png", scene.holdout.readColor(0), res, res);
    io::writeTextAtomically(o.out / "report.json", report.dump(2) + "\n");
    return report;
}

}  // namespace subdfit::fit
