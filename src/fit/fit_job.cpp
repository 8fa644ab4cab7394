#include "fit/fit_job.h"
#include "gl/platform_defines.h"

#include <chrono>
#include <cmath>

#include "context/gl_context.h"
#include "fit/cage_fitter.h"
#include "fit/checkpoint.h"
#include "fit/asset_export.h"
#include "fit/image_metrics.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "render/mesh_renderer.h"
#include "scene/scene_frame.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

using Clock = std::chrono::steady_clock;

struct ViewSetScore {
    double loss = 0.0, psnr = 0.0;
};

ViewSetScore score(CageFitter& fitter, const scene::TargetSet& targets) {
    render::RenderTarget image(targets.resolution(), targets.resolution());
    double loss = 0.0;
    for (int i = 0; i < targets.size(); ++i) {
        fitter.render(targets.camera(i), image);
        loss += meanPixelLoss(image.readColor(), targets.readColor(i));
    }
    loss /= std::max(1, targets.size());
    return {loss, psnrFromLoss(loss)};
}

std::vector<unsigned> triangleIndices(const mesh::PolygonMesh& triangles) {
    return {triangles.faceIndices.begin(), triangles.faceIndices.end()};
}

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

}  // namespace


nlohmann::json runFit(const FitOptions& o, const ProgressSink& progress, const std::atomic<bool>* cancel) {
    validate(o);
    const auto started = Clock::now();

    // Inputs, in the normalised frame of the reference.
    mesh::PolygonMesh cage = mesh::loadMesh(o.cage);
    mesh::PolygonMesh reference = mesh::triangulated(mesh::loadMesh(o.reference));
    const scene::SceneFrame frame = scene::frameAround(reference.positions);
    const auto cageWorld = cage;
    cage.positions = frame.toNormalized(cage.positions);
    reference.positions = frame.toNormalized(reference.positions);

    auto context = context::createHeadlessContext(o.glProvider);
    const auto glInfo = context::currentGlInfo();
    gl::ProgramCache programs(gl::platformDefines());

    const render::MeshRenderer referenceRenderer(reference.positions, mesh::vertexNormals(reference),
                                                 triangleIndices(reference));
    const scene::TargetSet training(programs, referenceRenderer, render::orbitCameras(o.views, o.seed),
                                    o.resolution);
    // Held-out views: another rotation of the lattice, so none coincides with a training view.
    const scene::TargetSet holdout(programs, referenceRenderer,
                                   render::orbitCameras(o.holdoutViews, o.seed ^ 0x9e3779b9u), o.resolution);

    CageFitSettings settings;
    settings.vertices.epsilon = o.epsilon;
    settings.vertices.learningRate = o.learningRate;
    settings.smoothingLambda = o.smoothing;
    settings.tessLevel = o.tessLevel;
    settings.resolution = o.resolution;
    settings.seed = o.seed;
    settings.plannedSteps = o.steps;
    settings.mapEffects = maps::parseMapEffects(o.maps);
    settings.maps.resolution = o.mapResolution;
    settings.mapsStartFraction = o.mapsStart;
    CageFitter fitter(programs, cage, settings);

    render::RenderTarget image(o.resolution, o.resolution);
    fitter.render(holdout.camera(0), image);
    const auto beforeImage = image.readColor();
    const ViewSetScore trainBefore = score(fitter, training);
    const ViewSetScore holdoutBefore = score(fitter, holdout);

    const auto checkpointPath = o.out / "checkpoint.bin";
    const std::string runFingerprint = checkpointFingerprint(o, cage, reference);
    int firstStep = 0;
    if (o.resume) {
        if (const auto saved = readCheckpoint(checkpointPath, runFingerprint)) {
            fitter.restore(*saved);
            firstStep = std::min(saved->steps, o.steps);
        }
    }
    auto saveCheckpoint = [&] {
        std::filesystem::create_directories(o.out);
        writeCheckpoint(checkpointPath, runFingerprint, fitter.state());
    };

    const auto fitStarted = Clock::now();
    const int reportEvery = std::max(1, o.steps / 50);
    int step = firstStep;
    for (; step < o.steps; ++step) {
        if (cancel && cancel->load()) break;
        // The loss is only read for progress, so about eight steps per report measure it.
        const bool measureLoss = step % std::max(1, reportEvery / 8) == 0;
        const auto views = viewsForStep(o, step);
        for (int sample = 0; sample < o.samplesPerStep; ++sample) fitter.accumulate(training, views, measureLoss);
        fitter.update();
        if (progress && ((step + 1) % reportEvery == 0 || step + 1 == o.steps)) {
            const double seconds = std::chrono::duration<double>(Clock::now() - fitStarted).count();
            const double done = double(step + 1 - firstStep);
            progress({step + 1, o.steps, fitter.takeMeanLoss(), seconds, seconds / done * double(o.steps - step - 1)});
        }
        if ((step + 1) % o.checkpointEvery == 0) saveCheckpoint();
    }
    saveCheckpoint();
    const double fitSeconds = std::chrono::duration<double>(Clock::now() - fitStarted).count();

    fitter.render(holdout.camera(0), image);
    const auto afterImage = image.readColor();
    const ViewSetScore trainAfter = score(fitter, training);
    const ViewSetScore holdoutAfter = score(fitter, holdout);
    const auto fitted = fitter.vertices();
    const bool finite = allFinite(fitter);

    nlohmann::json report = {
        {"steps", step},
        {"steps_requested", o.steps},
        {"resumed_from_step", firstStep},
        {"interrupted", step < o.steps},
        {"seconds", std::chrono::duration<double>(Clock::now() - started).count()},
        {"fit_seconds", fitSeconds},
        {"loss_initial", trainBefore.loss},
        {"loss_final", trainAfter.loss},
        {"psnr_train_initial", trainBefore.psnr},
        {"psnr_train", trainAfter.psnr},
        {"psnr_holdout_initial", holdoutBefore.psnr},
        {"psnr_holdout", holdoutAfter.psnr},
        {"finite", finite},
        {"effects", effectsJson(settings.mapEffects)},
        {"parameters", parametersJson(fitter)},
        {"renderer", glInfo.renderer},
        {"gl_version", glInfo.version},
        {"gl_provider", context->providerName()},
        {"atomic_float", glInfo.hasAtomicFloat},
        {"shader_variants", variantsJson(programs)},
        {"settings",
         {{"views", o.views}, {"holdout_views", o.holdoutViews}, {"resolution", o.resolution},
          {"views_per_step", o.viewsPerStep}, {"samples_per_step", o.samplesPerStep}, {"tess_level", fitter.renderer().tessLevel()},
          {"seed", o.seed}, {"epsilon", o.epsilon}, {"learning_rate", o.learningRate},
          {"smoothing", o.smoothing}, {"maps", o.maps}, {"map_resolution", o.mapResolution},
          {"maps_start", o.mapsStart}}},
        {"cage", {{"path", o.cage.string()}, {"vertices", cage.vertexCount()}, {"faces", cage.faceCount()},
                  {"patches", fitter.renderer().patchCount()}}},
        {"reference", {{"path", o.reference.string()}, {"triangles", reference.faceCount()}}},
    };

    // Outputs only now that everything has worked; each file appears whole or not at all.
    std::filesystem::create_directories(o.out);
    mesh::PolygonMesh fittedWorld = cageWorld;
    fittedWorld.positions = frame.toWorld(fitted);
    mesh::writeObj(o.out / "cage.obj", fittedWorld);
    report["exports"] = exportAsset(o, fitter, frame, fittedWorld);
    io::writeImage(o.out / "before.png", beforeImage, o.resolution, o.resolution);
    io::writeImage(o.out / "after.png", afterImage, o.resolution, o.resolution);
    io::writeImage(o.out / "target.png", holdout.readColor(0), o.resolution, o.resolution);
    io::writeTextAtomically(o.out / "report.json", report.dump(2) + "\n");
    return report;
}

}  // namespace subdfit::fit
