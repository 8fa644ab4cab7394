#include "fit/fit_options.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <nlohmann/json.hpp>

#include "maps/map_parameters.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

void require(bool ok, const std::string& what) {
    if (!ok) throw Error("invalid option: " + what);
}

}  // namespace

void validate(const FitOptions& o) {
    require(o.views >= 1 && o.views <= 1024, "--views must be in 1..1024, got " + std::to_string(o.views));
    require(o.holdoutViews >= 1 && o.holdoutViews <= 256, "held-out views must be in 1..256");
    require(o.resolution >= 16 && o.resolution <= 4096,
            "--res must be in 16..4096 pixels, got " + std::to_string(o.resolution));
    require(o.steps >= 0, "--steps must be >= 0, got " + std::to_string(o.steps));
    require(o.viewsPerStep >= 1 && o.viewsPerStep <= o.views, "--views-per-step must be in 1..--views");
    require(o.samplesPerStep >= 1 && o.samplesPerStep <= 64, "--samples-per-step must be in 1..64");
    require(o.tessLevel >= 1 && o.tessLevel <= 64, "--tess must be in 1..64");
    require(std::isfinite(o.epsilon) && o.epsilon > 0.0f && o.epsilon < 1.0f, "--epsilon must be in (0, 1)");
    require(std::isfinite(o.learningRate) && o.learningRate > 0.0f && o.learningRate < 1.0f,
            "--lr must be in (0, 1)");
    require(std::isfinite(o.smoothing) && o.smoothing >= 0.0f, "--smoothing must be >= 0");
    require(!o.out.empty(), "--out is required");
    require(o.checkpointEvery >= 1, "checkpoint interval must be >= 1 step");
    require(o.mapResolution >= 1 && o.mapResolution <= 64, "--map-res must be in 1..64, got " + std::to_string(o.mapResolution));
    require(o.mapsStart >= 0.0f && o.mapsStart <= 1.0f, "--maps-start must be in 0..1");
    maps::parseMapEffects(o.maps);
    if (std::filesystem::exists(o.out) && !std::filesystem::is_directory(o.out))
        throw fileError(o.out.string(), "exists and is not a folder");
}

nlohmann::json settingsJson(const FitOptions& o) {
    return {{"views", o.views},           {"holdout_views", o.holdoutViews},     {"resolution", o.resolution},
            {"steps", o.steps},           {"views_per_step", o.viewsPerStep},    {"samples_per_step", o.samplesPerStep},
            {"tess_level", o.tessLevel},  {"seed", o.seed},                      {"epsilon", o.epsilon},
            {"learning_rate", o.learningRate}, {"smoothing", o.smoothing},       {"maps", o.maps},
            {"map_resolution", o.mapResolution}, {"maps_start", o.mapsStart},    {"draco", o.draco},
            {"compact_maps", o.compactMaps}};
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
    return nlohmann::json{{"inputs", hash}, {"views", o.views}, {"holdout_views", o.holdoutViews},
                          {"resolution", o.resolution}, {"views_per_step", o.viewsPerStep}, {"samples_per_step", o.samplesPerStep},
                          {"tess", o.tessLevel},
                          {"seed", o.seed}, {"epsilon", o.epsilon}, {"lr", o.learningRate},
                          {"smoothing", o.smoothing}, {"maps", o.maps}, {"map_res", o.mapResolution},
                          {"maps_start", o.mapsStart}}
        .dump();
}

}  // namespace subdfit::fit
