#pragma once
// When a fit takes smaller steps and when it stops. Every few steps the loss of a few monitor
// views (another rotation of the view lattice than the training and the held-out views) is
// measured, and the parameters that gave the best one are kept. When it has not improved by
// kMinImprovement for kPatience measurements, the step is halved; after kMaxHalvings halvings
// (1/8 of the step, about where the old ×0.1 annealing ended) a further plateau ends the stage:
// it has converged. A poor start keeps the full step as long as it pays; a good one stops early.
// (FitRun returns to the best state at each halving.)
#include <cmath>

#include "fit/fit_state.h"

namespace subdfit::fit {

class StepSchedule {
public:
    static constexpr int kPatience = 4;
    static constexpr double kMinImprovement = 0.005;  // relative
    static constexpr int kMaxHalvings = 3;

    enum class Action { Continue, Halve, Converged };
    struct Decision {
        bool best;      // the best loss so far: keep these parameters
        Action action;
    };

    explicit StepSchedule(ScheduleState& state) : state_(state) {}

    // The monitored loss at `step`, and what to do about it.
    Decision record(double loss, int step);

    float learningRateScale() const { return std::ldexp(1.0f, -state_.halvings); }

    // A new stage (the maps joining): the full step again, and a best loss of its own.
    void restart() { state_ = ScheduleState{}; }

private:
    ScheduleState& state_;
};

}  // namespace subdfit::fit
