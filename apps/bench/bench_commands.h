#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "fit/fit_options.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/route.h"
#include "surface/relief_surface.h"

namespace subdfit::bench {

struct ReliefOptions {
    std::filesystem::path cage = "assets/spot/spot_control_mesh.obj";
    std::filesystem::path out = "relief_spot.glb";
    std::filesystem::path mesh;  // a textured triangle asset to split and relieve instead of the cage's limit surface
    int splits = 3;              // its triangles 4-split this many times
    surface::ReliefOptions relief;
};
int runRelief(const ReliefOptions& options);
// Writes options.out; returns its triangles (what runRelief prints, and simplify's default reference).
int writeReliefReference(const ReliefOptions& options);

struct StepCostOptions {
    std::filesystem::path out;
    int repeats = 40;  // interleaved rounds
    context::GlProvider glProvider = context::GlProvider::Auto;
    std::vector<int> resolutions{128, 256, 512};
    bool scaling = true;  // also the table of step time against parameter count
};
int runStepCost(const StepCostOptions& options);

struct LumpySphereOptions {
    std::filesystem::path out = "bench-lumpy-sphere";
    int steps = fit::kByDevice;  // the device's cap: the plateau schedule stops the fit once converged
    float noiseGate = fit::FitOptions{}.noiseGate;
    int resolution = 256;
    int views = 8;
    context::GlProvider glProvider = context::GlProvider::Auto;
    // The case: the lumpy sphere's bumps, their height (radius 1) and the seed placing them; the
    // cage's quads per cube-face edge (6: 216 quads).
    int bumps = 12;
    float amplitude = 0.15f;
    std::uint32_t lumpsSeed = 1;
    int cageDivisions = 6;
    std::uint32_t seed = 1;  // the fit's (views, perturbations)
};
int runLumpySphere(const LumpySphereOptions& options);

struct ConvergenceOptions {
    std::filesystem::path out = "bench-convergence";
    fit::FitOptions fit;      // the fit's defaults unless told otherwise
    float startScale = 0.7f;  // the cage's size against the reference's
    // The lumpy sphere: its bumps, their height (radius 1) and the seed placing them.
    int bumps = 12;
    float amplitude = 0.15f;
    std::uint32_t seed = 1;
    int every = 25;  // steps between Chamfer measurements
    double peerChamfer = 7.07e-4;
};
int runConvergence(const ConvergenceOptions& options);

struct RecoveryOptions {
    std::filesystem::path out = "bench-recovery";
    std::vector<std::filesystem::path> shapes{
        "assets/osd-shapes/catmark_cube_creases1.obj", "assets/osd-shapes/catmark_pyramid_creases0.obj",
        "assets/osd-shapes/catmark_single_crease.obj", "assets/osd-shapes/catmark_chaikin0.obj",
        "assets/osd-shapes/catmark_helmet.obj",        "assets/osd-shapes/catmark_bishop.obj"};
    fit::FitOptions fit = [] {
        fit::FitOptions f;
        f.views = 8;
        return f;
    }();                  // steps: the device's cap; the plateau schedule stops each fit once converged
    float sigma = 0.03f;  // noise, a fraction of the scene radius
    std::uint32_t noiseSeed = 11;
};
int runRecovery(const RecoveryOptions& options);

struct FitGainOptions {
    std::filesystem::path out = "bench-fit-gain";
    std::filesystem::path cage, reference;  // a good start (e.g. simplify's initial_cage.obj) and its dense reference
    int faces = 0;                          // > 0: start from simplify's initial cage of this many faces instead
    fit::FitOptions fit;                    // common to every variant; with --maps, baked onto the cage first
    std::vector<std::string> variants;      // "key=value;key=value" over fit (report.json's option keys)
    int every = 10;                         // steps per turn (and between held-out scores)
};
int runFitGain(const FitGainOptions& options);

struct MapsGainOptions {
    std::filesystem::path out = "bench-maps";
    // The case: a cage and a reference; a cage alone: its limit surface with a relief of this
    // RMS height (a fraction of the bounding-box diagonal) as the reference; neither: a sphere
    // covered in small bumps over the ~200-quad sphere cage.
    std::filesystem::path cage, reference;
    float reliefAmplitude = 0.006f;
    std::uint32_t reliefSeed = 1;
    fit::FitOptions fit;  // steps: the device's cap; the plateau schedule stops each fit once converged
    // The maps each compared with a vertex-only fit ("none"), in turn.
    std::vector<std::string> compared{"displacement", "displacement,normal"};
};
int runMapsGain(const MapsGainOptions& options);

struct AccuracyOptions {
    std::filesystem::path out = "bench-accuracy";
    int baseSteps = 400;
    context::GlProvider glProvider = context::GlProvider::Auto;
};
int runAccuracy(const AccuracyOptions& options);

struct GradientOptions {
    std::filesystem::path out = "bench-gradient";
    int maxSamples = 256;
    int sweepSamples = 64;
    float epsilon = 0.008f;  // the fit's default vertex ε; also the finite-difference step
    context::GlProvider glProvider = context::GlProvider::Auto;
};
int runGradientQuality(const GradientOptions& options);

struct SoupOptions {
    std::filesystem::path out = "bench-soup";
    int triangles = 100000;
    int steps = 250;
    int resolution = 512;
    double seconds = 0.0;  // step time per estimator (0: no limit); with --steps, whichever ends first
    context::GlProvider glProvider = context::GlProvider::Auto;
};
int runSoup(const SoupOptions& options);

struct SimplifyTradeoffOptions {
    std::filesystem::path out = "bench-simplify";
    std::vector<std::filesystem::path> references;  // none: the relief Spot, written into out
    std::vector<std::uintmax_t> budgets{2000, 5000, 10000, 20000, 50000, 100000, 200000};
    int steps = fit::kByDevice;
    int resolution = fit::kByDevice;
    context::GlProvider glProvider = context::GlProvider::Auto;
    simplify::CompareLevel compare = simplify::CompareLevel::Full;
    simplify::CageShape cageShape = simplify::CageShape::Auto;
};
int runSimplifyTradeoff(const SimplifyTradeoffOptions& options);

struct DecodeLodsOptions {
    std::filesystem::path asset;      // an asset.subd
    std::filesystem::path reference;  // its dense reference (optional)
    std::filesystem::path out = "bench-lods";
    int lods = 4;
};
int runDecodeLods(const DecodeLodsOptions& options);

struct SubdPrefixOptions {
    std::filesystem::path asset;              // the asset.subd whose prefixes are decoded
    std::vector<std::filesystem::path> made;  // files made for their own budgets, scored whole
    std::filesystem::path reference;          // the dense reference they were made from
    std::filesystem::path out = "bench-prefix";
    int cuts = 16;  // prefixes from the cage's end to the file's end
    // --grow T,BITS: cut a file grown from the asset instead (subd_prefix.cpp); 0: the asset itself
    int growResolution = 0, growBits = 0;
    int prefixBits = 4;  // the asset's own bits: the grown file's first levels are coded at them
    context::GlProvider glProvider = context::GlProvider::Auto;
};
int runSubdPrefix(const SubdPrefixOptions& options);

}  // namespace subdfit::bench
