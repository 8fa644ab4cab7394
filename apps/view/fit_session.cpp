#include "fit_session.h"

#include <cstdio>

#include "fit/device_defaults.h"
#include "fit/shipped_asset.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "util/json_text.h"

namespace subdfit::view {

FitInputs loadFitInputs(const fit::FitOptions& options) {
    return {mesh::loadMesh(options.cage), mesh::loadReference(options.reference)};
}

FitInputs refineInputs(const ResultInputs& result, fit::FitOptions& options) {
    const ColumnInputs* reference = nullptr;
    const ColumnInputs* ours = nullptr;
    const ColumnInputs* fittedCage = nullptr;  // beside a triangle route that shipped instead
    for (const auto& column : result.columns) {
        if (column.reference) reference = &column;
        if (column.name == "subdfit" && column.levels.front().asset) ours = &column;
        if (column.name == "cage" && column.levels.front().asset) fittedCage = &column;
    }
    if (!ours) ours = fittedCage;
    if (!result.folder || !reference || !ours)
        throw Error(result.title +
                    ": nothing to refine: --refine takes a fit or simplify folder whose reference is there");
    const codec::SubdAsset& asset = *ours->levels.front().asset;
    const surface::SurfaceMaps& maps = asset.maps;
    options.cage = ours->levels.front().path;
    options.reference = result.folder->reference;
    options.maps = maps.kinds() & maps::MapEffects::on(kinds::MapLattice::Geometric);
    if (maps.layout.resolution > 0) options.mapResolution = maps.layout.resolution;
    options.shadingNormal = maps.shadingNormal;
    options.appearanceAtlas = maps.appearanceAtlas.size;
    if (!maps.appearanceAtlas.present() && maps.appearanceLayout.resolution > 0)
        options.appearanceResolution = maps.appearanceLayout.resolution;
    // How the result was coded and shaded, so that Save ships it alike.
    const nlohmann::json& settings = result.folder->settings;
    try {
        options.mapBits = settings.value("map_bits", options.mapBits);
        options.appearanceQuality = settings.value("appearance_quality", options.appearanceQuality);
        if (settings.contains("shading")) fit::setOption(options, "shading", settings["shading"].get<std::string>());
        options.compactMaps = settings.value("compact_maps", options.compactMaps);
    } catch (const nlohmann::json::exception&) {
        throw fileError((result.folder->dir / "report.json").string(), "its settings are not what subdfit writes");
    } catch (const Error& e) {
        throw fileError((result.folder->dir / "report.json").string(), std::string("its settings: ") + e.what());
    }
    options.mapsStart = 0.0f;  // the maps are already fitted: they refine with the cage from the start
    return {.cage = asset.cage, .reference = reference->levels.front().mesh, .start = maps};
}

FitSession::FitSession(const fit::FitOptions& given, FitInputs inputs) : programs_(gl::platformDefines()) {
    fit::validate(given);
    fit::FitOptions options = given;
    if (const std::string chosen = fit::resolveForCurrentDevice(options); !chosen.empty())
        std::fprintf(stderr, "subdfit-view: %s\n", chosen.c_str());
    const fit::ResolvedFitOptions checked = fit::resolved(options);
    scene_ = std::make_unique<fit::FitScene>(checked, programs_, std::move(inputs.cage), inputs.reference);
    run_ = std::make_unique<fit::FitRun>(checked, programs_, *scene_);
    if (inputs.start) run_->startFrom(fit::normalizedMaps(*inputs.start, scene_->frame));
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
    io::writeTextAtomically(out / "report.json", jsonText(report, 2));
    run_->saveCheckpoint(out / "checkpoint.bin");
    return report;
}

}  // namespace subdfit::view
