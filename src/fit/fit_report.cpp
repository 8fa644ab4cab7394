#include "fit/fit_report.h"

#include "io/input_file.h"
#include "util/error.h"

namespace subdfit::fit {

nlohmann::json referenceJson(const std::filesystem::path& reference, int triangles) {
    nlohmann::json out{{"path", reference.string()}, {"triangles", triangles}};
    try {
        out["xxh3_128"] = io::fileDigest(reference);
    } catch (const Error&) {
        // Not a file (a test's mesh in memory) or gone: the path alone, which no viewer opens.
    }
    return out;
}

nlohmann::json toJson(const FitReport& r) {
    auto effects = nlohmann::json::array({"subdivision"});
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds)
        if (r.effects.has(kind.kind)) effects.push_back(kind.name);
    nlohmann::json parameters = nlohmann::json::object();
    for (const auto& [group, count] : r.parameters) parameters[group] = count;
    auto variants = nlohmann::json::array();
    for (const auto& variant : r.shaderVariants) {
        nlohmann::json defines = nlohmann::json::object();
        for (const auto& [name, value] : variant.defines) defines[name] = value;
        variants.push_back({{"name", variant.name}, {"files", variant.files}, {"defines", defines}});
    }
    nlohmann::json settings = settingsJson(r.options);
    settings["tess_level"] = r.tessLevel;
    nlohmann::json exports = nlohmann::json::object();
    for (const auto& [file, bytes] : r.exports) exports[file] = bytes;
    // What each step cost in accuracy, as the schedule saw it: compact rows a plot reads directly.
    auto monitored = nlohmann::json::array();
    for (const MonitorMeasurement& m : r.monitored) monitored.push_back({m.step, m.seconds, m.loss});
    nlohmann::json report{
        {"steps", r.steps},
        {"steps_requested", r.options.steps},
        {"resumed_from_step", r.resumedFromStep},
        {"interrupted", r.interrupted()},
        {"seconds", r.seconds},
        {"fit_seconds", r.fitSeconds},
        {"psnr_holdout_initial", r.holdoutBefore.psnr},
        {"psnr_holdout", r.holdoutAfter.psnr},
        // How the held-out views are scored: each pixel the mean of this many samples (anti-aliased).
        {"holdout_samples_per_pixel", r.holdoutSamplesPerPixel},
        {"finite", r.finite},
        {"effects", effects},
        {"parameters", parameters},
        {"renderer", r.gl.renderer},
        {"gl_version", r.gl.version},
        {"gl_provider", r.glProvider},
        {"atomic_float", r.gl.hasAtomicFloat},
        {"shader_variants", variants},
        {"settings", settings},
        {"cage",
         {{"path", r.options.cage.string()},
          {"vertices", r.cageVertices},
          {"faces", r.cageFaces},
          {"patches", r.patches},
          {"creases", r.cageCreases},
          {"corners", r.cageCorners}}},
        {"reference", referenceJson(r.options.reference, r.referenceTriangles)},
        {"exports", exports},
        {"stop_reason", r.stopReason},
        {"best_step", r.bestStep},
        {"monitor_losses", monitored},
    };
    if (r.trainBefore && r.trainAfter) {
        report["loss_initial"] = r.trainBefore->loss;
        report["loss_final"] = r.trainAfter->loss;
        report["psnr_train_initial"] = r.trainBefore->psnr;
        report["psnr_train"] = r.trainAfter->psnr;
    }
    return report;
}

}  // namespace subdfit::fit
