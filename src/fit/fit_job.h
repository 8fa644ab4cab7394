#pragma once
// `subdfit fit`: load a cage and a reference, render targets, fit the cage's control vertices,
// write cage.obj, report.json and before/after/target images of a held-out view into a folder.
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

namespace subdfit::fit {

struct FitOptions {
    std::filesystem::path cage, reference, out;
    int views = 24;          // training views (held-out views come in addition)
    int holdoutViews = 6;
    int resolution = 256;
    int steps = 500;
    int viewsPerStep = 1;
    int tessLevel = 8;
    std::uint32_t seed = 1;
    float epsilon = 0.008f;       // vertex perturbation, in units of the normalised scene (radius 1)
    float learningRate = 0.004f;  // Adam step, same units; annealed ×0.1 over the run
    float smoothing = 4.0f;       // λ of the Laplacian preconditioner (0: off)
    std::string glProvider = "auto";
    std::string maps = "none";    // none | displacement | normal | displacement,normal
    int mapResolution = 8;        // cells per ptex-face edge of each map tile
    bool draco = false;           // fitted.glb with KHR_draco_mesh_compression
    bool resume = false;          // continue from out/checkpoint.bin when it exists
    int checkpointEvery = 100;    // steps between checkpoints (also written on interrupt and at the end)
};

struct Progress {
    int step, steps;
    float loss;
    double seconds, etaSeconds;
};

using ProgressSink = std::function<void(const Progress&)>;

// Throws subdfit::Error for bad options or inputs before anything is written. `cancel`, when
// set during the fit, stops it early and still writes the results of the steps taken.
nlohmann::json runFit(const FitOptions& options, const ProgressSink& progress = {},
                      const std::atomic<bool>* cancel = nullptr);

void validate(const FitOptions& options);

}  // namespace subdfit::fit
