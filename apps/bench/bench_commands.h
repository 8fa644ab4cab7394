#pragma once
#include <filesystem>
#include <string>

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

}  // namespace subdfit::bench
