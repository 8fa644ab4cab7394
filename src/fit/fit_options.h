#pragma once
// What a user asks of `subdfit fit`, checked; and the pure functions of those options that a
// resumed run must reproduce exactly (the view schedule, the checkpoint fingerprint).
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mesh/polygon_mesh.h"

namespace subdfit::fit {

struct FitOptions {
    std::filesystem::path cage, reference, out;
    int views = 24;          // training views (held-out views come in addition)
    int holdoutViews = 6;
    int resolution = 256;
    int steps = 500;
    int viewsPerStep = 1;
    int samplesPerStep = 1;       // perturbations averaged per Adam step
    int tessLevel = 8;
    std::uint32_t seed = 1;
    float epsilon = 0.008f;       // vertex perturbation, in units of the normalised scene (radius 1)
    float learningRate = 0.004f;  // Adam step, same units; annealed ×0.1 over the run
    float smoothing = 4.0f;       // λ of the Laplacian preconditioner (0: off)
    std::string glProvider = "auto";
    std::string maps = "none";    // none | displacement | normal | displacement,normal
    int mapResolution = 8;        // cells per ptex-face edge of each map tile
    float mapsStart = 0.4f;       // fraction of the steps fitted by the cage alone before maps join
    bool draco = false;           // fitted.glb with KHR_draco_mesh_compression
    bool compactMaps = false;     // ship maps as HALF EXR and 8-bit PNG (export/map_atlas.h)
    bool resume = false;          // continue from out/checkpoint.bin when it exists
    bool force = false;           // write into a non-empty folder that holds no subdfit results
    int checkpointEvery = 100;    // steps between checkpoints (also written on interrupt and at the end)
};

// Throws subdfit::Error ("invalid option: ...") for anything impossible, before any work.
void validate(const FitOptions& options);

// The settings that shape the result (not where it goes, not how often it is checkpointed, not
// which GL provider runs it), for the report and for telling one run's output from another's.
nlohmann::json settingsJson(const FitOptions& options);

// The training views of step `step`: shuffled rounds over all views, every view equally often.
// A pure function of (seed, step), so a resumed run visits exactly what the first would have.
std::vector<int> viewsForStep(const FitOptions& options, int step);

// What must match for a checkpoint to be resumed: the inputs' geometry and the settings that
// shape the optimisation (not the step count, so a finished run can be extended).
std::string checkpointFingerprint(const FitOptions& options, const mesh::PolygonMesh& cage,
                                  const mesh::PolygonMesh& reference);

}  // namespace subdfit::fit
