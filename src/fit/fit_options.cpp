#include "fit/fit_options.h"

#include "context/gl_context.h"
#include "render/shading_model.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <sstream>
#include <type_traits>

namespace subdfit::fit {
namespace detail {

const std::vector<OptionRow>& optionTable() {
    using F = FitOptions;
    // key, flag, help, range, resumable, setting
    static const std::vector<OptionRow> rows = {
        {{"views", "--views", "training views on a sphere (default: 24, 48 on a GPU)", 1, 1024, false, true, true, true},
         &F::views},
        {{"holdout_views", "--holdout-views", "held-out evaluation views", 1, 256, false, true, true}, &F::holdoutViews},
        {{"resolution", "--res", "render resolution in pixels (default: 256, 512 on a GPU)", 16, 4096, false, true, true, true},
         &F::resolution},
        {{"steps", "--steps", "optimisation steps, the most with --schedule plateau, which stops once converged (default: 4000, 20000 on a GPU)", 0, 1e9,
          false, false, true, true},
         &F::steps},
        {{"views_per_step", "--views-per-step", "views rendered per step", 1, 1024, false, true, true}, &F::viewsPerStep},
        {{"samples_per_step", "--samples-per-step", "perturbations averaged per step", 1, 64, false, true, true},
         &F::samplesPerStep},
        {{"tess_level", "--tess", "tessellation segments per face edge (half on cages of over 2 000 faces)", 1, 64, false, true, true}, &F::tessLevel},
        {{"seed", "--seed", "random seed (views, perturbations)", 1, 0, false, true, true}, &F::seed},
        {{"epsilon", "--epsilon", "vertex perturbation, a fraction of the cage's mean edge (at most ~1 pixel)", 0, 1, true, true, true},
         &F::epsilon},
        {{"learning_rate", "--lr", "vertex learning rate, a fraction of the cage's mean edge (at most ~0.5 pixel)", 0, 1, true, true, true},
         &F::learningRate},
        {{"smoothing", "--smoothing", "Laplacian preconditioner λ (0 = off); on cages with edges under 1/4 of the scene radius, x (1/4 / edge)^2", 0, 1e6, false, true, true},
         &F::smoothing},
        {{"noise_gate", "--noise-gate",
          "noise gate c: a parameter's step shrinks to 0 as its mean gradient falls to c times its noise (0 = plain Adam)",
          0, 100, false, true, true},
         &F::noiseGate},
        {{"relaxation", "--relax", "tangential relaxation of the cage per step (0 = off)", 0, 1, false, true, true},
         &F::relaxation},
        {{"tangential", "--tangential", "fraction of the vertex gradient along the surface kept (1 = all)", 0, 1,
          false, true, true},
         &F::tangential},
        {{"shading", "--shading", "auto (what the reference's materials call for), geometry, unlit, lambert, pbr", 1, 0,
          false, true, true},
         &F::shading},
        {{"maps", "--maps", "maps to fit: none, displacement, normal, displacement,normal", 1, 0, false, true, true},
         &F::maps},
        {{"map_resolution", "--map-res", "map cells per face edge", 1, 64, false, true, true}, &F::mapResolution},
        {{"shading_normal", "--shading-normal",
          "what shades displaced heights: displaced (their slopes tilt the normal) or limit (the limit surface's "
          "normal, the heights only place it); simplify --budget chooses", 1, 0, false, true, true},
         &F::shadingNormal},
        {{"appearance_resolution", "--appearance-res",
          "base colour / metallic-roughness cells per face edge (scenes with materials)", 1, 64, false, true, true},
         &F::appearanceResolution},
        {{"appearance_atlas", "--appearance-atlas",
          "simplify: texels per side of the base colour / metallic-roughness in the reference's own UV atlas "
          "(0 = tiles per face; a reference with one textured material)", 0, 4096, false, true, true},
         &F::appearanceAtlas},
        {{"maps_start", "--maps-start", "fraction of the steps before the maps join", 0, 1, false, true, true},
         &F::mapsStart},
        {{"map_bits", "--map-bits", "bits per map value in asset.subd, over each channel's range", 4, 16, false, false, true},
         &F::mapBits},
        {{"appearance_quality", "--appearance-quality",
          "JPEG quality (1-100) of the base colour / metallic-roughness images in asset.subd", 1, 100, false, false, true},
         &F::appearanceQuality},
        {{"preview", "--preview", "also write fitted.glb: the displaced limit surface, --tess segments per face edge",
          1, 0, false, false, true},
         &F::preview},
        {{"draco", "--draco", "compress the exported meshes with Draco", 1, 0, false, false, true}, &F::draco},
        {{"usd", "--usd", "USD export of the shipped asset: usdz (asset.usdz), usdz,usda (and the layer's text beside it), none",
          1, 0, false, false, true},
         &F::usd},
        {{"compact_maps", "", "ship maps as HALF EXR and 8-bit PNG", 1, 0, false, false, true}, &F::compactMaps},
        {{"resume", "--resume", "continue from DIR/checkpoint.bin (same inputs and settings)"}, &F::resume},
        {{"force", "--force", "write into --out even if it holds other files"}, &F::force},
        {{"checkpoint_every", "--checkpoint-every", "steps between checkpoints", 1, 1e9}, &F::checkpointEvery},
        {{"gl", "--gl", context::kGlProviderHelp}, &F::glProvider},
        {{"schedule", "--schedule",
          "plateau: halve the step when the fit stalls, stop when converged (steps: the most); anneal: x0.1 over the steps",
          1, 0, false, true, true},
         &F::schedule},
    };
    return rows;
}

}  // namespace detail

namespace {

template <class T>
void checkRange(const OptionInfo& info, T value) {
    if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
        if (info.min > info.max) return;
        if (info.byDevice && value == T(kByDevice)) return;
        const double v = double(value);
        const bool inside = std::isfinite(v) && (info.openRange ? v > info.min && v < info.max : v >= info.min && v <= info.max);
        if (!inside) {
            std::ostringstream problem;  // (streams: GCC 12 misreads the string concatenations, -Wrestrict)
            problem << "must be in " << (info.openRange ? "(" : "") << info.min << (info.openRange ? ", " : "..")
                    << info.max << (info.openRange ? ")" : "") << ", got " << v;
            throw OptionError(info.key, problem.str());
        }
    }
}

template <class T>
nlohmann::json toJson(const T& value) {
    if constexpr (std::is_same_v<T, maps::MapEffects>) return maps::toString(value);
    else return value;
}

}  // namespace

std::string optionFlag(const std::string& key) {
    for (const auto& row : detail::optionTable())
        if (key == row.info.key) return row.info.flag;
    return "";
}

void setOption(FitOptions& options, const std::string& key, const std::string& value) {
    bool found = false;
    forEachOption(options, [&](const OptionInfo& info, auto& field) {
        using T = std::decay_t<decltype(field)>;
        if (key != info.key) return;
        found = true;
        try {
            if constexpr (std::is_same_v<T, bool>) field = value == "1" || value == "true";
            else if constexpr (std::is_same_v<T, std::string>) field = value;
            else if constexpr (std::is_same_v<T, maps::MapEffects>) field = maps::parseMapEffects(value);
            else if constexpr (std::is_same_v<T, float>) field = std::stof(value);
            else field = T(std::stoll(value));
        } catch (const std::exception&) {
            throw OptionError(key, "cannot read '" + value + "'");
        }
    });
    if (!found) throw OptionError(key, "is not a fit option");
}

void validate(const FitOptions& o) {
    forEachOption(o, [](const OptionInfo& info, const auto& value) { checkRange(info, value); });
    if (o.views != kByDevice && o.viewsPerStep > o.views) throw OptionError("views_per_step", "must be at most views (" + std::to_string(o.views) + ")");
    if (o.out.empty()) throw OptionError("out", "is required");
    if (o.shading != "auto") {
        try {
            render::parseShadingModel(o.shading);
        } catch (const Error& e) {
            throw OptionError("shading", e.what());
        }
    }
    if (o.appearanceAtlas == 1) throw OptionError("appearance_atlas", "must be 0 (tiles) or at least 2 texels");
    if (o.shadingNormal != "displaced" && o.shadingNormal != "limit")
        throw OptionError("shading_normal", "must be displaced or limit, got '" + o.shadingNormal + "'");
    if (o.usd != "usdz" && o.usd != "usdz,usda" && o.usd != "none")
        throw OptionError("usd", "must be usdz, usdz,usda or none, got '" + o.usd + "'");
    if (o.schedule != "plateau" && o.schedule != "anneal")
        throw OptionError("schedule", "must be plateau or anneal, got '" + o.schedule + "'");
}

void validateResolved(const FitOptions& o) {
    validate(o);
    forEachOption(o, [](const OptionInfo& info, const auto& value) {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, int>)
            if (info.byDevice && value == kByDevice)
                throw OptionError(info.key, "left to the device, but no device chose it (resolveDeviceDefaults)");
    });
}

nlohmann::json settingsJson(const FitOptions& o) {
    nlohmann::json settings = nlohmann::json::object();
    forEachOption(o, [&](const OptionInfo& info, const auto& value) {
        if (info.setting) settings[info.key] = toJson(value);
    });
    return settings;
}

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

std::string checkpointFingerprint(const FitOptions& o, const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference) {
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
    auto mix = [&](const void* data, size_t bytes) {
        for (size_t i = 0; i < bytes; ++i) hash = (hash ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
    };
    for (const auto* m : {&cage, &reference}) {
        mix(m->positions.data(), m->positions.size() * sizeof(glm::vec3));
        mix(m->faceIndices.data(), m->faceIndices.size() * sizeof(int));
    }
    nlohmann::json fingerprint = {{"inputs", hash}};
    forEachOption(o, [&](const OptionInfo& info, const auto& value) {
        if (info.resumable) fingerprint[info.key] = toJson(value);
    });
    return fingerprint.dump();
}

}  // namespace subdfit::fit
