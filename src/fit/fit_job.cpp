#include "fit/fit_job.h"

#include <chrono>
#include <cmath>
#include <numeric>
#include <random>

#include "context/gl_context.h"
#include "fit/cage_fitter.h"
#include "fit/checkpoint.h"
#include "export/glb_writer.h"
#include "export/limit_tessellation.h"
#include "export/map_atlas.h"
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

void require(bool ok, const std::string& what) {
    if (!ok) throw Error("invalid option: " + what);
}

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

bool allFinite(const std::vector<glm::vec3>& points) {
    for (const auto& p : points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    return true;
}

// The training views of step `step`: shuffled rounds over all views, every view equally often.
// A pure function of (seed, step), so a resumed run visits exactly what the first would have.
std::vector<int> viewsForStep(const FitOptions& o, int step) {
    std::vector<int> views;
    for (int j = 0; j < o.viewsPerStep; ++j) {
        const long long k = (long long)step * o.viewsPerStep + j;
        const long long round = k / o.views;
        std::vector<int> order(size_t(o.views));
        std::iota(order.begin(), order.end(), 0);
        std::mt19937 rng(std::uint32_t(o.seed * 2654435761u + std::uint32_t(round)));
        std::shuffle(order.begin(), order.end(), rng);
        views.push_back(order[size_t(k % o.views)]);
    }
    return views;
}

// What must match for a checkpoint to be resumed: the inputs' geometry and the settings that
// shape the optimisation (not the step count, so a finished run can be extended).
std::string fingerprint(const FitOptions& o, const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference) {
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
    auto mix = [&](const void* data, size_t bytes) {
        for (size_t i = 0; i < bytes; ++i) hash = (hash ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
    };
    for (const auto* m : {&cage, &reference}) {
        mix(m->positions.data(), m->positions.size() * sizeof(glm::vec3));
        mix(m->faceIndices.data(), m->faceIndices.size() * sizeof(int));
    }
    return nlohmann::json{{"inputs", hash}, {"views", o.views}, {"holdout_views", o.holdoutViews},
                          {"resolution", o.resolution}, {"views_per_step", o.viewsPerStep}, {"tess", o.tessLevel},
                          {"seed", o.seed}, {"epsilon", o.epsilon}, {"lr", o.learningRate},
                          {"smoothing", o.smoothing}, {"maps", o.maps}, {"map_res", o.mapResolution}}
        .dump();
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

// displacement.exr, normal.png, maps.json (when the scene has maps) and fitted.glb: the cage's
// limit surface tessellated as rendered, displaced, with the normal map, in world units.
nlohmann::json exportAsset(const FitOptions& o, CageFitter& fitter, const scene::SceneFrame& frame,
                           const mesh::PolygonMesh& fittedWorld) {
    exporter::FittedMaps maps;
    std::vector<exporter::WrittenFile> written;
    std::vector<unsigned char> normalPng;
    if (auto* parameters = fitter.maps()) {
        maps.layout = parameters->layout();
        if (auto* g = parameters->displacement()) {
            maps.displacement = g->read();
            for (float& d : maps.displacement) d /= frame.scale;  // heights back to world units
        }
        if (auto* g = parameters->normalMap()) maps.normal = g->read();
        written = exporter::writeMapAtlases(o.out, maps);
        if (maps.hasNormal()) normalPng = exporter::encodeNormalPng(exporter::atlasLayout(maps.layout), maps);
    } else {
        maps.layout = maps::buildTexelLayout(fittedWorld, 1);  // no maps: UVs still name each face's tile
    }
    const auto tessellation = exporter::tessellateLimitSurface(fittedWorld, maps, fitter.renderer().tessLevel());
    written.push_back(exporter::writeFittedGlb(o.out / "fitted.glb", tessellation, normalPng, o.draco));
    nlohmann::json files = nlohmann::json::object();
    for (const auto& file : written) files[file.path.filename().string()] = file.bytes;
    return files;
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

void validate(const FitOptions& o) {
    require(o.views >= 1 && o.views <= 1024, "--views must be in 1..1024, got " + std::to_string(o.views));
    require(o.holdoutViews >= 1 && o.holdoutViews <= 256, "held-out views must be in 1..256");
    require(o.resolution >= 16 && o.resolution <= 4096,
            "--res must be in 16..4096 pixels, got " + std::to_string(o.resolution));
    require(o.steps >= 0, "--steps must be >= 0, got " + std::to_string(o.steps));
    require(o.viewsPerStep >= 1 && o.viewsPerStep <= o.views, "--views-per-step must be in 1..--views");
    require(o.tessLevel >= 1 && o.tessLevel <= 64, "--tess must be in 1..64");
    require(std::isfinite(o.epsilon) && o.epsilon > 0.0f && o.epsilon < 1.0f, "--epsilon must be in (0, 1)");
    require(std::isfinite(o.learningRate) && o.learningRate > 0.0f && o.learningRate < 1.0f,
            "--lr must be in (0, 1)");
    require(std::isfinite(o.smoothing) && o.smoothing >= 0.0f, "--smoothing must be >= 0");
    require(!o.out.empty(), "--out is required");
    require(o.checkpointEvery >= 1, "checkpoint interval must be >= 1 step");
    require(o.mapResolution >= 1 && o.mapResolution <= 64, "--map-res must be in 1..64, got " + std::to_string(o.mapResolution));
    maps::parseMapEffects(o.maps);
    if (std::filesystem::exists(o.out) && !std::filesystem::is_directory(o.out))
        throw fileError(o.out.string(), "exists and is not a folder");
}

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
    gl::ProgramCache programs(glInfo.hasAtomicFloat ? gl::Defines{{"SUBDFIT_ATOMIC_FLOAT", ""}} : gl::Defines{});

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
    CageFitter fitter(programs, cage, settings);

    render::RenderTarget image(o.resolution, o.resolution);
    fitter.render(holdout.camera(0), image);
    const auto beforeImage = image.readColor();
    const ViewSetScore trainBefore = score(fitter, training);
    const ViewSetScore holdoutBefore = score(fitter, holdout);

    const auto checkpointPath = o.out / "checkpoint.bin";
    const std::string runFingerprint = fingerprint(o, cage, reference);
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
        fitter.step(training, viewsForStep(o, step), step % std::max(1, reportEvery / 8) == 0);
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
    const bool finite = allFinite(fitted);

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
          {"views_per_step", o.viewsPerStep}, {"tess_level", fitter.renderer().tessLevel()},
          {"seed", o.seed}, {"epsilon", o.epsilon}, {"learning_rate", o.learningRate},
          {"smoothing", o.smoothing}, {"maps", o.maps}, {"map_resolution", o.mapResolution}}},
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
