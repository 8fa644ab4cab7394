#include "fit/fit_options.h"

#include "surface/appearance_atlas.h"

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
    static const std::vector<OptionRow> rows = {
        {{.key = "views",
          .flag = "--views",
          .help = "training views on a sphere (default: 24, 48 on a GPU)",
          .min = 1,
          .max = 1024,
          .resumable = true,
          .setting = true,
          .byDevice = true},
         &F::views},
        {{.key = "holdout_views",
          .flag = "--holdout-views",
          .help = "held-out evaluation views",
          .min = 1,
          .max = 256,
          .resumable = true,
          .setting = true},
         &F::holdoutViews},
        {{.key = "resolution",
          .flag = "--res",
          .help = "render resolution in pixels (default: 256, 512 on a GPU)",
          .min = 16,
          .max = 4096,
          .resumable = true,
          .setting = true,
          .byDevice = true},
         &F::resolution},
        {{.key = "steps",
          .flag = "--steps",
          .help = "optimisation steps, the most with --schedule plateau, which stops once converged (default: 4000, "
                  "20000 on a GPU)",
          .min = 0,
          .max = 1e9,
          .setting = true,
          .byDevice = true},
         &F::steps},
        {{.key = "views_per_step",
          .flag = "--views-per-step",
          .help = "views rendered per step",
          .min = 1,
          .max = 1024,
          .resumable = true,
          .setting = true},
         &F::viewsPerStep},
        {{.key = "samples_per_step",
          .flag = "--samples-per-step",
          .help = "perturbations averaged per step",
          .min = 1,
          .max = 64,
          .resumable = true,
          .setting = true},
         &F::samplesPerStep},
        {{.key = "tess_level",
          .flag = "--tess",
          .help = "tessellation segments per face edge, at least (more where a face spans many pixels, half on cages "
                  "of over 2 000 faces)",
          .min = 1,
          .max = 64,
          .resumable = true,
          .setting = true},
         &F::tessLevel},
        {{.key = "seed",
          .flag = "--seed",
          .help = "random seed (views, perturbations)",
          .resumable = true,
          .setting = true},
         &F::seed},
        {{.key = "epsilon",
          .flag = "--epsilon",
          .help = "vertex perturbation, a fraction of the cage's mean edge (at most ~1 pixel)",
          .min = 0,
          .max = 1,
          .openRange = true,
          .resumable = true,
          .setting = true},
         &F::epsilon},
        {{.key = "learning_rate",
          .flag = "--lr",
          .help = "vertex learning rate, a fraction of the cage's mean edge (at most ~0.5 pixel)",
          .min = 0,
          .max = 1,
          .openRange = true,
          .resumable = true,
          .setting = true},
         &F::learningRate},
        {{.key = "smoothing",
          .flag = "--smoothing",
          .help = "Laplacian preconditioner λ (0 = off); on cages with edges under 1/4 of the scene radius, x (1/4 / "
                  "edge)^2",
          .min = 0,
          .max = 1e6,
          .resumable = true,
          .setting = true},
         &F::smoothing},
        {{.key = "noise_gate",
          .flag = "--noise-gate",
          .help = "noise gate c: a parameter's step shrinks to 0 as its mean gradient falls to c times its noise (0 = "
                  "plain Adam)",
          .min = 0,
          .max = 100,
          .resumable = true,
          .setting = true},
         &F::noiseGate},
        {{.key = "relaxation",
          .flag = "--relax",
          .help = "tangential relaxation of the cage per step (0 = off)",
          .min = 0,
          .max = 1,
          .resumable = true,
          .setting = true},
         &F::relaxation},
        {{.key = "tangential",
          .flag = "--tangential",
          .help = "fraction of the vertex gradient along the surface kept (1 = all; the images barely constrain it)",
          .min = 0,
          .max = 1,
          .resumable = true,
          .setting = true},
         &F::tangential},
        {{.key = "shading",
          .flag = "--shading",
          .help = "auto (what the reference's materials call for), geometry, unlit, lambert, pbr",
          .resumable = true,
          .setting = true},
         &F::shading},
        {{.key = "maps",
          .flag = "--maps",
          .help = "maps to fit: none, displacement, normal, displacement,normal",
          .resumable = true,
          .setting = true},
         &F::maps},
        {{.key = "map_resolution",
          .flag = "--map-res",
          .help = "map cells per face edge",
          .min = 1,
          .max = 64,
          .resumable = true,
          .setting = true},
         &F::mapResolution},
        {{.key = "shading_normal",
          .flag = "--shading-normal",
          .help = "what shades displaced heights: displaced (their slopes tilt the normal) or limit (the limit "
                  "surface's normal, the heights only place it); simplify --budget chooses",
          .resumable = true,
          .setting = true},
         &F::shadingNormal},
        {{.key = "appearance_resolution",
          .flag = "--appearance-res",
          .help = "base colour / metallic-roughness cells per face edge (scenes with materials)",
          .min = 1,
          .max = 64,
          .resumable = true,
          .setting = true},
         &F::appearanceResolution},
        {{.key = "appearance_atlas",
          .flag = "--appearance-atlas",
          .help = "simplify: texels per side of the base colour / metallic-roughness in the reference's own UV atlas "
                  "(0 = tiles per face; a reference with one textured material)",
          .min = 0,
          .max = surface::kMaxAtlasSize,
          .resumable = true,
          .setting = true},
         &F::appearanceAtlas},
        {{.key = "maps_start",
          .flag = "--maps-start",
          .help = "fraction of the steps before the maps join",
          .min = 0,
          .max = 1,
          .resumable = true,
          .setting = true},
         &F::mapsStart},
        {{.key = "map_bits",
          .flag = "--map-bits",
          .help = "bits per map value in asset.subd, over each channel's range",
          .min = 4,
          .max = 16,
          .setting = true},
         &F::mapBits},
        {{.key = "position_bits",
          .flag = "--position-bits",
          .help = "bits per cage coordinate in asset.subd, over the cage's bounding cube (simplify --budget chooses)",
          .min = 8,
          .max = 16,
          .setting = true},
         &F::positionBits},
        {{.key = "appearance_quality",
          .flag = "--appearance-quality",
          .help = "JPEG quality (1-100) of the base colour / metallic-roughness images in asset.subd",
          .min = 1,
          .max = 100,
          .setting = true},
         &F::appearanceQuality},
        {{.key = "preview",
          .flag = "--preview",
          .help = "also write fitted.glb: the displaced limit surface, --tess segments per face edge",
          .setting = true},
         &F::preview},
        {{.key = "draco", .flag = "--draco", .help = "compress the exported meshes with Draco", .setting = true},
         &F::draco},
        {{.key = "usd",
          .flag = "--usd",
          .help =
              "USD export of the shipped asset: usdz (asset.usdz), usdz,usda (and the layer's text beside it), none",
          .setting = true},
         &F::usd},
        {{.key = "compact_maps", .flag = "", .help = "ship maps as HALF EXR and 8-bit PNG", .setting = true},
         &F::compactMaps},
        {{.key = "resume", .flag = "--resume", .help = "continue from DIR/checkpoint.bin (same inputs and settings)"},
         &F::resume},
        {{.key = "force", .flag = "--force", .help = "write into --out even if it holds other files"}, &F::force},
        {{.key = "checkpoint_every",
          .flag = "--checkpoint-every",
          .help = "steps between checkpoints",
          .min = 1,
          .max = 1e9},
         &F::checkpointEvery},
        {{.key = "gl", .flag = "--gl", .help = "GL provider: auto (OSMesa, else EGL), osmesa, egl"}, &F::glProvider},
        {{.key = "schedule",
          .flag = "--schedule",
          .help = "plateau: halve the step when the fit stalls, stop when converged (steps: the most); anneal: x0.1 "
                  "over the steps",
          .resumable = true,
          .setting = true},
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
        const bool inside =
            std::isfinite(v) && (info.openRange ? v > info.min && v < info.max : v >= info.min && v <= info.max);
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
    if constexpr (WordOption<T>) return optionText(value);
    else return value;
}

}  // namespace

const OptionInfo* findOption(std::string_view key) {
    for (const auto& row : detail::optionTable())
        if (key == row.info.key) return &row.info;
    return nullptr;
}

std::string optionFlag(const std::string& key) {
    const OptionInfo* info = findOption(key);
    return info ? info->flag : "";
}

void setOption(FitOptions& options, const std::string& key, const std::string& value) {
    bool found = false;
    forEachOption(options, [&](const OptionInfo& info, auto& field) {
        using T = std::decay_t<decltype(field)>;
        if (key != info.key) return;
        found = true;
        try {
            if constexpr (std::is_same_v<T, bool>) field = value == "1" || value == "true";
            else if constexpr (WordOption<T>) readOptionText(info, field, value);
            else if constexpr (std::is_same_v<T, float>) field = std::stof(value);
            else field = T(std::stoll(value));
        } catch (const OptionError&) {
            throw;
        } catch (const std::exception&) {
            throw OptionError(key, "cannot read '" + value + "'");
        }
    });
    if (!found) throw OptionError(key, "is not a fit option");
}

void validate(const FitOptions& o) {
    forEachOption(o, [](const OptionInfo& info, const auto& value) { checkRange(info, value); });
    if (o.views != kByDevice && o.viewsPerStep > o.views)
        throw OptionError("views_per_step", "must be at most views (" + std::to_string(o.views) + ")");
    if (o.out.empty()) throw OptionError("out", "is required");
    if (o.appearanceAtlas == 1) throw OptionError("appearance_atlas", "must be 0 (tiles) or at least 2 texels");
}

ResolvedFitOptions resolved(FitOptions o) {
    validate(o);
    forEachOption(o, [](const OptionInfo& info, const auto& value) {
        if constexpr (std::is_same_v<std::decay_t<decltype(value)>, int>)
            if (info.byDevice && value == kByDevice)
                throw OptionError(info.key, "left to the device, but no device chose it (resolveDeviceDefaults)");
    });
    return ResolvedFitOptions(std::move(o));
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

std::string checkpointFingerprint(const FitOptions& o, const mesh::PolygonMesh& cage,
                                  const mesh::PolygonMesh& reference) {
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
    auto mix = [&](const void* data, size_t bytes) {
        for (size_t i = 0; i < bytes; ++i)
            hash = (hash ^ static_cast<const unsigned char*>(data)[i]) * 1099511628211ull;
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
