#pragma once
// When a fit takes smaller steps and when it stops. Every few steps the loss of a few monitor
// views (another rotation of the view lattice than the training and the held-out views) is
// measured, and the parameters that gave the best one are kept. That loss is noisy (the
// parameters jitter under the estimator's noise), so no single comparison decides: a line is
// fitted to the last window of measurements, and the fit is still improving while a relative
// fall of kMinImprovement per kWindow measurements stays likely (the fitted fall plus
// kConfidence standard errors reaches it). When it is not, the step is halved and a fresh window
// starts, twice as long as the last (up to kMostWindowDoublings times): a halved step falls more
// slowly against the same noise, and a longer window tells a slow fall from a flat line. After
// kMaxHalvings halvings a further stall ends the stage: it has converged. A poor start keeps
// the full step as long as it pays; a good one stops early. (FitRun returns to the best state
// at each halving.)
#include <cmath>
#include <vector>

#include "fit/fit_state.h"

namespace subdfit::fit {

// A least-squares line through a series of losses, one per measurement: the relative fall it
// shows over the series' span and that fall's standard error (infinite with fewer than 3).
struct LossTrend {
    double fall = 0.0, standardError = INFINITY;
};
LossTrend lossTrend(const std::vector<double>& losses);

// Whether `trend` leaves a relative fall of at least `minFall` likely: its estimate plus
// `confidence` standard errors reaches it.
bool likelyImproving(const LossTrend& trend, double minFall, double confidence);

class StepSchedule {
public:
    static constexpr int kWindow = 10;  // measurements per decision at the full step
    static constexpr int kMostWindowDoublings = 2;
    static constexpr double kMinImprovement = 0.005;  // relative fall per kWindow measurements worth going on for
    static constexpr double kConfidence = 0.5;        // standard errors: stall when P(fall >= min) < ~30 %
    static constexpr int kMaxHalvings = 3;
    // A probation gives the benefit of the doubt: it stops a stage only when even its fall plus
    // this many standard errors stays short (a poor start's first steps can be erratic).
    static constexpr double kProbationConfidence = 2.0;
    // A probation's loss that rose and is falling again by this much from its highest responds
    // to the steps: the first ones (Adam's moments still hold few samples) overshot.
    static constexpr double kRebound = 0.01;
    // A probation that stops only a rise (ScheduleState::probationStopsOnlyARise) stops a stage
    // whose loss rose by at least this much even at its fall plus kProbationConfidence standard
    // errors; a flat one goes on.
    static constexpr double kClearRise = 0.01;

    enum class Action { Continue, Halve, Converged };
    struct Decision {
        bool best;  // the best loss so far: keep these parameters
        Action action;
    };

    // `windowDoublings`: the most times halvings double the window. A fit from a poor start
    // gains on slow falls; a refinement of a near-optimal start (simplify's bake) gains little
    // there for its seconds (0: every window kWindow measurements).
    explicit StepSchedule(ScheduleState& state, int windowDoublings = kMostWindowDoublings)
        : state_(state), windowDoublings_(windowDoublings) {}

    // The monitored loss at `step`, and what to do about it.
    Decision record(double loss, int step);

    float learningRateScale() const { return std::ldexp(1.0f, -state_.halvings); }
    // Measurements per decision at the current step.
    int window() const;
    // The cage's: it also keeps the halvings it carried into this stage.
    float vertexRateScale() const { return std::ldexp(1.0f, -(state_.halvings + state_.carriedHalvings)); }

    // Whether the stage pays: its measurements since its start (at least 3, at most kWindow)
    // leave a fall of kMinImprovement plausible (kProbationConfidence). For a fit's probation (FitRun): a start it cannot
    // improve on is given up early.
    bool paying() const;

    // A probation's verdict (FitRun). A stage whose loss fell by kMinImprovement below its start
    // and then rose again, or rose and is falling again by kRebound, can be improved; its step is
    // too large for it (a noised cage's first full steps gain, or overshoot, and the estimator's
    // noise walks it away): halve() and go on from the best. A stage that never fell, with no
    // fall likely, cannot pay. On a probation that stops only a rise, a stage pays unless its
    // loss clearly rose (kClearRise); on the later one that asks a gain, it pays if its last
    // window's mean lies kMinImprovement below its start (a gain that holds, not one early best)
    // or that window (of half a window's measurements at least) makes a fall that large likely
    // (kProbationConfidence).
    enum class Verdict { Paying, StepTooLarge, NoGain };
    Verdict probation() const;
    // Whether the stage's first measurements (a window's) show a clear rise: kClearRise even at
    // their fall plus kProbationConfidence standard errors. A later probation that sees one ends
    // then (FitRun): a start the steps make steadily worse is not waiting to fall.
    bool clearlyRose() const;
    // The step halved by hand, with a fresh window.
    void halve();
    // A probation's StepTooLarge: the step halved, and the stage on probation again from its
    // best state (measured at `step`), so that the halved step pays or is given up as the start
    // would be: a fall that was only the monitor's noise costs one probation, not a stage.
    void retryFromBest(int step);

    // A new stage (the maps joining): the full step again, and a best loss of its own.
    void restart() { state_ = ScheduleState{}; }

private:
    ScheduleState& state_;
    int windowDoublings_;
};

}  // namespace subdfit::fit
