#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace subdfit::bench {

struct StepCostOptions {
    std::filesystem::path out;
    int repeats = 15;
    std::string glProvider = "auto";
};
int runStepCost(const StepCostOptions& options);

struct LumpySphereOptions {
    std::filesystem::path out = "bench-lumpy-sphere";
    int steps = 500;
    int resolution = 256;
    int views = 8;
    std::string glProvider = "auto";
};
int runLumpySphere(const LumpySphereOptions& options);

struct MapsGainOptions {
    std::filesystem::path out = "bench-maps";
    int steps = 800;
    int mapResolution = 8;
    std::string glProvider = "auto";
};
int runMapsGain(const MapsGainOptions& options);

struct AccuracyOptions {
    std::filesystem::path out = "bench-accuracy";
    int baseSteps = 400;
    std::string glProvider = "auto";
};
int runAccuracy(const AccuracyOptions& options);

struct GradientOptions {
    std::filesystem::path out = "bench-gradient";
    int maxSamples = 256;
    int sweepSamples = 64;
    float epsilon = 0.008f;  // the fit's default vertex ε; also the finite-difference step
    std::string glProvider = "auto";
};
int runGradientQuality(const GradientOptions& options);

struct SoupOptions {
    std::filesystem::path out = "bench-soup";
    int triangles = 100000;
    int steps = 250;
    int resolution = 512;
    double seconds = 0.0;  // step time per estimator (0: no limit); with --steps, whichever ends first
    std::string glProvider = "auto";
};
int runSoup(const SoupOptions& options);

struct SimplifyTradeoffOptions {
    std::filesystem::path out = "bench-simplify";
    std::filesystem::path reference = "assets/spot/spot_triangulated.obj";
    std::vector<int> faces{100, 300, 1000};
    std::vector<std::string> maps{"none", "2", "4"};  // "none" or a map resolution (both maps)
    int steps = 300;
    int resolution = 128;
    std::string glProvider = "auto";
};
int runSimplifyTradeoff(const SimplifyTradeoffOptions& options);

}  // namespace subdfit::bench
