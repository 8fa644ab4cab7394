#include "fit/fit_job.h"

#include <chrono>
#include <cmath>
#include <numeric>
#include <random>

#include "context/gl_context.h"
#include "fit/cage_fitter.h"
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
    CageFitter fitter(programs, cage, settings);

    render::RenderTarget image(o.resolution, o.resolution);
    fitter.render(holdout.camera(0), image);
    const auto beforeImage = image.readColor();
    const ViewSetScore trainBefore = score(fitter, training);
    const ViewSetScore holdoutBefore = score(fitter, holdout);

    // Views visited in shuffled rounds: every view equally often, in no fixed order.
    std::mt19937 rng(o.seed);
    std::vector<int> order(size_t(o.views));
    std::iota(order.begin(), order.end(), 0);
    size_t cursor = order.size();
    std::vector<int> batch(size_t(o.viewsPerStep));

    const auto fitStarted = Clock::now();
    const int reportEvery = std::max(1, o.steps / 50);
    int step = 0;
    for (; step < o.steps; ++step) {
        if (cancel && cancel->load()) break;
        for (auto& view : batch) {
            if (cursor == order.size()) {
                std::shuffle(order.begin(), order.end(), rng);
                cursor = 0;
            }
            view = order[cursor++];
        }
        fitter.step(training, batch);
        if (progress && ((step + 1) % reportEvery == 0 || step + 1 == o.steps)) {
            const double seconds = std::chrono::duration<double>(Clock::now() - fitStarted).count();
            progress({step + 1, o.steps, fitter.takeMeanLoss(), seconds,
                      seconds / double(step + 1) * double(o.steps - step - 1)});
        }
    }
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
        {"seconds", std::chrono::duration<double>(Clock::now() - started).count()},
        {"fit_seconds", fitSeconds},
        {"loss_initial", trainBefore.loss},
        {"loss_final", trainAfter.loss},
        {"psnr_train_initial", trainBefore.psnr},
        {"psnr_train", trainAfter.psnr},
        {"psnr_holdout_initial", holdoutBefore.psnr},
        {"psnr_holdout", holdoutAfter.psnr},
        {"finite", finite},
        {"effects", {"subdivision"}},
        {"parameters", {{"vertices", fitter.parameterCount()}}},
        {"renderer", glInfo.renderer},
        {"gl_version", glInfo.version},
        {"gl_provider", context->providerName()},
        {"atomic_float", glInfo.hasAtomicFloat},
        {"shader_variants", variantsJson(programs)},
        {"settings",
         {{"views", o.views}, {"holdout_views", o.holdoutViews}, {"resolution", o.resolution},
          {"views_per_step", o.viewsPerStep}, {"tess_level", fitter.renderer().tessLevel()},
          {"seed", o.seed}, {"epsilon", o.epsilon}, {"learning_rate", o.learningRate},
          {"smoothing", o.smoothing}}},
        {"cage", {{"path", o.cage.string()}, {"vertices", cage.vertexCount()}, {"faces", cage.faceCount()},
                  {"patches", fitter.renderer().patchCount()}}},
        {"reference", {{"path", o.reference.string()}, {"triangles", reference.faceCount()}}},
    };

    // Outputs only now that everything has worked; each file appears whole or not at all.
    std::filesystem::create_directories(o.out);
    mesh::PolygonMesh fittedWorld = cageWorld;
    fittedWorld.positions = frame.toWorld(fitted);
    mesh::writeObj(o.out / "cage.obj", fittedWorld);
    io::writeImage(o.out / "before.png", beforeImage, o.resolution, o.resolution);
    io::writeImage(o.out / "after.png", afterImage, o.resolution, o.resolution);
    io::writeImage(o.out / "target.png", holdout.readColor(0), o.resolution, o.resolution);
    io::writeTextAtomically(o.out / "report.json", report.dump(2) + "\n");
    return report;
}

}  // namespace subdfit::fit
