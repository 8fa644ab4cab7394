#include "fit_session.h"

#include <cstdio>

#include "fit/device_defaults.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"

namespace subdfit::view {

FitInputs loadFitInputs(const fit::FitOptions& options) {
    return {mesh::loadMesh(options.cage), mesh::loadReference(options.reference)};
}

FitSession::FitSession(const fit::FitOptions& given, FitInputs inputs) : programs_(gl::platformDefines()) {
    fit::validate(given);
    fit::FitOptions options = given;
    if (const std::string chosen = fit::resolveForCurrentDevice(options); !chosen.empty())
        std::fprintf(stderr, "subdfit-view: %s\n", chosen.c_str());
    scene_ = std::make_unique<fit::FitScene>(options, programs_, std::move(inputs.cage), inputs.reference);
    run_ = std::make_unique<fit::FitRun>(options, programs_, *scene_);
    meanEdge_ = mesh::meanEdgeLength(scene_->cage);
    if (options.resume) run_->resume(options.out / "checkpoint.bin");
}

void FitSession::step() {
    if (!anythingOptimised()) return;  // a step would only count itself
    run_->advance(true);
    // The readback waits for the step to finish, so the viewer's time budget sees its real cost.
    losses_.push_back(run_->takeMeanLoss());
}

bool FitSession::anythingOptimised() {
    for (auto* g : fitter().groups())
        if (fitter().optimised(*g)) return true;
    return false;
}

nlohmann::json FitSession::save(const context::GlContext& context, const std::filesystem::path& out) {
    // The report's settings say what the vertices were fitted with last, knobs included.
    fit::FitOptions& options = run_->options();
    options = fit::withVertexRates(options, run_->scene().cage, fitter().vertexGroup().settings());
    fit::validate(options);
    const auto report = fit::toJson(run_->writeResults(out, context));
    io::writeTextAtomically(out / "report.json", report.dump(2) + "\n");
    run_->saveCheckpoint(out / "checkpoint.bin");
    return report;
}

}  // namespace subdfit::view
