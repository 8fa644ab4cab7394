#include "fit/step_schedule.h"

namespace subdfit::fit {

StepSchedule::Decision StepSchedule::record(double loss, int step) {
    const bool best = std::isfinite(loss) && loss < state_.bestLoss;
    const bool significant = best && loss < state_.bestLoss * (1.0 - kMinImprovement);
    if (best) {
        state_.bestLoss = loss;
        state_.bestStep = step;
    }
    if (significant) {
        state_.sinceImprovement = 0;
        return {best, Action::Continue};
    }
    if (++state_.sinceImprovement < kPatience) return {best, Action::Continue};
    state_.sinceImprovement = 0;
    if (state_.halvings >= kMaxHalvings) return {best, Action::Converged};
    ++state_.halvings;
    return {best, Action::Halve};
}

}  // namespace subdfit::fit
