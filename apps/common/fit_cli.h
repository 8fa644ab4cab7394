#pragma once
// The fit options of `subdfit fit`, registered once for every app that runs a fit (the batch
// command and the viewer), so that both accept the same flags with the same defaults and help.
// Each app adds its own --out (and whatever else is its own).
#include <CLI/CLI.hpp>

#include "fit/fit_options.h"

namespace subdfit::apps {

// Everything that shapes the fit but its inputs (`simplify` makes its own cage).
inline void addFitSettings(CLI::App& app, fit::FitOptions& fit) {
    app.add_option("--views", fit.views, "training views on a sphere")->capture_default_str();
    app.add_option("--holdout-views", fit.holdoutViews, "held-out evaluation views")->capture_default_str();
    app.add_option("--res", fit.resolution, "render resolution in pixels")->capture_default_str();
    app.add_option("--steps", fit.steps, "optimisation steps")->capture_default_str();
    app.add_option("--seed", fit.seed, "random seed (views, perturbations)")->capture_default_str();
    app.add_option("--views-per-step", fit.viewsPerStep, "views rendered per step")->capture_default_str();
    app.add_option("--samples-per-step", fit.samplesPerStep, "perturbations averaged per step")->capture_default_str();
    app.add_option("--tess", fit.tessLevel, "tessellation segments per face edge")->capture_default_str();
    app.add_option("--epsilon", fit.epsilon, "vertex perturbation (scene radius = 1)")->capture_default_str();
    app.add_option("--lr", fit.learningRate, "vertex learning rate (scene radius = 1)")->capture_default_str();
    app.add_option("--smoothing", fit.smoothing, "Laplacian preconditioner strength (0 = off)")->capture_default_str();
    app.add_option("--maps", fit.maps, "maps to fit: none, displacement, normal, displacement,normal")->capture_default_str();
    app.add_option("--map-res", fit.mapResolution, "map cells per face edge")->capture_default_str();
    app.add_option("--maps-start", fit.mapsStart, "fraction of the steps before the maps join")->capture_default_str();
    app.add_flag("--draco", fit.draco, "compress the exported meshes with Draco");
    app.add_flag("--resume", fit.resume, "continue from DIR/checkpoint.bin (same inputs and settings)");
    app.add_flag("--force", fit.force, "write into --out even if it holds other files");
    app.add_option("--checkpoint-every", fit.checkpointEvery, "steps between checkpoints")->capture_default_str();
}

inline void addFitOptions(CLI::App& app, fit::FitOptions& fit) {
    app.add_option("--cage", fit.cage, "control cage (.obj with OpenSubdiv tags, .gltf, .glb, .drc)")->required();
    app.add_option("--reference", fit.reference, "reference mesh to match (.obj, .gltf, .glb, .drc)")->required();
    addFitSettings(app, fit);
}

}  // namespace subdfit::apps
