#pragma once
// Everything a resumed fit needs to continue exactly where one stopped: plain data, so that the
// checkpoint format (fit/checkpoint.h) is read and written without a GL context.
#include <cstdint>
#include <limits>
#include <vector>

namespace subdfit::fit {

struct GroupState {
    std::vector<float> theta{}, moment1{}, moment2{};
    float groupMoment2 = 0.0f;  // the second moment shared by the group (its own moments: moment2)
    int adamSteps = 0;
};

// Where the step schedule (fit/step_schedule.h) stands: the best monitored loss so far and the
// parameters that gave it, the measurements its decisions weigh, how often the step was halved.
struct ScheduleState {
    double bestLoss = std::numeric_limits<double>::infinity();
    int bestStep = -1;
    std::vector<double> window{};       // the last monitored losses since the last halving
    std::vector<double> stageLosses{};  // the stage's first few, for its probation
    int stageStart = -1;                // the step of its first measurement
    bool probationOver = false;
    bool probationStopsOnlyARise = false;  // a near-optimal start that may lie flat before it falls
    bool probationAsksAGain = false;       // the later probation of one that passed the above
    int halvings = 0;
    int carriedHalvings = 0;  // the cage's, from the stage before: its step is 2^-(halvings + these)
    std::vector<std::vector<float>> bestTheta{};   // per group, in CageFitter::groups() order; empty: none yet
    std::vector<std::vector<float>> startTheta{};  // the same at the stage's first measurement
};

// One measurement of the monitored loss (fit/step_schedule.h): at which step, after how many
// seconds of steps, and the loss.
struct MonitorMeasurement {
    int step = 0;
    double seconds = 0.0, loss = 0.0;
    friend bool operator==(const MonitorMeasurement&, const MonitorMeasurement&) = default;
};

struct FitState {
    int steps = 0;
    std::uint32_t samples = 0;
    std::vector<GroupState> groups{};  // in CageFitter::groups() order
    float learningRateScale = -1.0f;   // set by a schedule; < 0: the fitter's own annealing
    int mapsStartStep = -1;            // set when the maps were started early; < 0: the planned step
    ScheduleState schedule{};
    std::vector<MonitorMeasurement> monitored{};  // every measurement so far, for the report
};

}  // namespace subdfit::fit
