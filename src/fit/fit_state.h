#pragma once
// Everything a resumed fit needs to continue exactly where one stopped: plain data, so that the
// checkpoint format (fit/checkpoint.h) is read and written without a GL context.
#include <cstdint>
#include <limits>
#include <vector>

namespace subdfit::fit {

struct GroupState {
    std::vector<float> theta{}, moment1{}, moment2{};
    int adamSteps = 0;
};

// Where the step schedule (fit/step_schedule.h) stands: the best monitored loss so far and the
// parameters that gave it, how long since it improved, how often the step was halved.
struct ScheduleState {
    double bestLoss = std::numeric_limits<double>::infinity();
    int bestStep = -1;
    int sinceImprovement = 0;  // monitor evaluations
    int halvings = 0;
    std::vector<std::vector<float>> bestTheta{};  // per group, in CageFitter::groups() order; empty: none yet
};

struct FitState {
    int steps = 0;
    std::uint32_t samples = 0;
    std::vector<GroupState> groups{};  // in CageFitter::groups() order
    float learningRateScale = -1.0f;   // set by a schedule; < 0: the fitter's own annealing
    int mapsStartStep = -1;            // set when the maps were started early; < 0: the planned step
    int widenedStep = -1;              // when FitRun::run widened its last stage; < 0: not (yet)
    ScheduleState schedule{};
};

}  // namespace subdfit::fit
