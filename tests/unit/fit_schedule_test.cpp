// How long a fit runs and with what: the plateau schedule's decisions, and the options a device
// chooses when the user did not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fit/device_defaults.h"
#include "fit/step_schedule.h"

namespace subdfit::fit {
namespace {

// Relative noise, uniform in [-amplitude, amplitude], from a generator whose output the
// standard fixes: the same sequence on every platform.
class Noise {
public:
    explicit Noise(double amplitude, unsigned seed = 7) : amplitude_(amplitude), rng_(seed) {}
    double operator()() { return 1.0 + amplitude_ * (2.0 * double(rng_()) / double(std::mt19937::max()) - 1.0); }

private:
    double amplitude_;
    std::mt19937 rng_;
};

TEST(LossTrend, ALineGivesItsFallExactly) {
    const LossTrend trend = lossTrend({1.0, 0.9, 0.8, 0.7, 0.6});
    EXPECT_NEAR(trend.fall, 0.4 / 0.8, 1e-12);  // over the span, relative to the mean level
    EXPECT_NEAR(trend.standardError, 0.0, 1e-12);
    EXPECT_FALSE(std::isfinite(lossTrend({1.0, 0.5}).standardError));  // two points say nothing of noise
    EXPECT_FALSE(likelyImproving(lossTrend({1.0, 0.5}), 0.0, 1.0));
}

TEST(StepSchedule, ANoisyButImprovingLossKeepsTheFullStepAndTheBest) {
    ScheduleState state;
    StepSchedule schedule(state);
    // Noise four times the fall of one measurement: a single comparison with the best so far
    // (which the noise pulls low) would call nearly every such sequence a plateau.
    Noise noise(0.04);
    double level = 1.0;
    int bestCount = 0;
    for (int k = 0; k < 80; ++k, level *= 0.99) {
        const auto decision = schedule.record(level * noise(), 10 * k);
        EXPECT_EQ(decision.action, StepSchedule::Action::Continue) << "measurement " << k;
        bestCount += decision.best;
    }
    EXPECT_EQ(state.halvings, 0);
    EXPECT_GT(bestCount, 20);  // the best moves on with the loss
    EXPECT_GT(state.bestStep, 700);
    EXPECT_FLOAT_EQ(schedule.learningRateScale(), 1.0f);
    EXPECT_TRUE(schedule.paying());
}

TEST(StepSchedule, AFlatNoisyLossHalvesThenConverges) {
    ScheduleState state;
    StepSchedule schedule(state);
    Noise noise(0.04);
    int halvings = 0, measurements = 0, firstHalving = -1;
    StepSchedule::Action action = StepSchedule::Action::Continue;
    while (action != StepSchedule::Action::Converged && measurements < 400) {
        action = schedule.record(noise(), measurements++).action;
        if (action == StepSchedule::Action::Halve && halvings++ == 0) firstHalving = measurements;
    }
    EXPECT_EQ(action, StepSchedule::Action::Converged);
    EXPECT_EQ(halvings, StepSchedule::kMaxHalvings);
    // Never on fewer measurements than a window, and each stall on a fresh one, longer after
    // each halving.
    int windows = 0;
    for (int h = 0; h <= StepSchedule::kMaxHalvings; ++h)
        windows += StepSchedule::kWindow << std::min(h, StepSchedule::kMostWindowDoublings);
    EXPECT_EQ(firstHalving, StepSchedule::kWindow);
    EXPECT_GE(measurements, windows);
    EXPECT_LE(measurements, 2 * windows);
    EXPECT_FLOAT_EQ(schedule.learningRateScale(), 1.0f / 8.0f);
}

TEST(StepSchedule, AHalvedStepIsJudgedOnALongerWindow) {
    ScheduleState state;
    StepSchedule schedule(state);
    EXPECT_EQ(schedule.window(), StepSchedule::kWindow);
    state.halvings = 1;
    EXPECT_EQ(schedule.window(), 2 * StepSchedule::kWindow);
    state.halvings = StepSchedule::kMaxHalvings;
    EXPECT_EQ(schedule.window(), StepSchedule::kWindow << StepSchedule::kMostWindowDoublings);
    // A refinement of a near-optimal start keeps the full step's window.
    EXPECT_EQ(StepSchedule(state, 0).window(), StepSchedule::kWindow);
}

TEST(StepSchedule, ASlowNoisyFallAfterHalvingsIsNoStall) {
    // A halved step falls slowly against the noise: here three times the least fall worth going
    // on for, under noise of ±3 % a measurement. Judged on windows of kWindow measurements, such
    // a fall is taken for a plateau within a few hundred; on the longer window the halvings
    // bring, it is not.
    constexpr double kFallPerMeasurement = 3.0 * StepSchedule::kMinImprovement / StepSchedule::kWindow;
    for (unsigned seed = 1; seed <= 5; ++seed) {
        ScheduleState halved, full;
        halved.halvings = StepSchedule::kMostWindowDoublings;
        StepSchedule halvedSchedule(halved), fullSchedule(full);
        Noise noise(0.03, seed);
        double level = 1.0;
        int fullStalls = 0;
        for (int k = 0; k < 400; ++k, level *= 1.0 - kFallPerMeasurement) {
            const double loss = level * noise();
            EXPECT_EQ(halvedSchedule.record(loss, k).action, StepSchedule::Action::Continue)
                << "seed " << seed << ", measurement " << k;
            fullStalls += fullSchedule.record(loss, k).action != StepSchedule::Action::Continue;
            full.halvings = 0;  // stays at the full step's window
        }
        EXPECT_GT(fullStalls, 0) << "seed " << seed;
    }
}

TEST(StepSchedule, ASteadyFallTooSmallToPayForIsAStall) {
    ScheduleState state;
    StepSchedule schedule(state);
    double loss = 1.0;
    StepSchedule::Action action = StepSchedule::Action::Continue;
    int k = 0;
    for (; k < StepSchedule::kWindow && action == StepSchedule::Action::Continue; ++k) {
        loss *= 1.0 - StepSchedule::kMinImprovement / 16;  // better every time, but not worth the time
        const auto decision = schedule.record(loss * (1.0 + 1e-5 * (k % 2)), k);
        action = decision.action;
    }
    EXPECT_EQ(action, StepSchedule::Action::Halve);
    EXPECT_EQ(k, StepSchedule::kWindow);
}

TEST(StepSchedule, ANonFiniteLossIsNeverTheBest) {
    ScheduleState state;
    StepSchedule schedule(state);
    schedule.record(1.0, 0);
    EXPECT_FALSE(schedule.record(std::nan(""), 1).best);
    EXPECT_EQ(state.bestStep, 0);
}

TEST(StepSchedule, AStartThatGainsIsPayingOneThatDoesNotIsNot) {
    ScheduleState gaining, flat;
    StepSchedule gainingSchedule(gaining), flatSchedule(flat);
    Noise noise(0.002);
    for (int k = 0; k < 5; ++k) {
        gainingSchedule.record((1.0 - 0.01 * k) * noise(), 5 * k);
        flatSchedule.record(noise(), 5 * k);
    }
    EXPECT_TRUE(gainingSchedule.paying());
    EXPECT_FALSE(flatSchedule.paying());
    EXPECT_EQ(flat.stageStart, 0);
}

TEST(StepSchedule, AProbationThatFellOrOvershotHalvesTheStepOneThatNeverFellStops) {
    // A noised start's first full steps gain, then the estimator's noise walks it away: the
    // step is too large, not the start beyond improvement.
    ScheduleState fellThenRose, flat, gaining;
    StepSchedule fellSchedule(fellThenRose), flatSchedule(flat), gainingSchedule(gaining);
    const std::vector<double> fellLosses = {1.0, 0.92, 1.06, 1.19, 1.31, 1.39};
    Noise noise(0.002);
    for (size_t k = 0; k < fellLosses.size(); ++k) {
        fellSchedule.record(fellLosses[k], 5 * int(k));
        flatSchedule.record(1.0 + 0.01 * double(k) * noise(), 5 * int(k));  // rising, never below the start
        gainingSchedule.record((1.0 - 0.01 * double(k)) * noise(), 5 * int(k));
    }
    EXPECT_EQ(fellSchedule.probation(), StepSchedule::Verdict::StepTooLarge);
    EXPECT_EQ(flatSchedule.probation(), StepSchedule::Verdict::NoGain);
    // A noised creased cube at 512²: its first steps overshot (+21 %), the next ones came back.
    ScheduleState overshot;
    StepSchedule overshotSchedule(overshot);
    const std::vector<double> overshotLosses = {1.0, 1.07, 1.18, 1.21, 1.21, 1.13};
    for (size_t k = 0; k < overshotLosses.size(); ++k) overshotSchedule.record(overshotLosses[k], 5 * int(k));
    EXPECT_EQ(overshotSchedule.probation(), StepSchedule::Verdict::StepTooLarge);
    EXPECT_EQ(gainingSchedule.probation(), StepSchedule::Verdict::Paying);
    fellSchedule.retryFromBest(30);
    EXPECT_FLOAT_EQ(fellSchedule.learningRateScale(), 0.5f);
    EXPECT_TRUE(fellThenRose.window.empty());
    // On probation again, from the best state: its loss is the new start.
    EXPECT_FALSE(fellThenRose.probationOver);
    EXPECT_EQ(fellThenRose.stageStart, 30);
    EXPECT_EQ(fellThenRose.stageLosses, std::vector<double>{0.92});
    // The halved step that only holds the best gains nothing: given up as a start would be.
    for (int k = 1; k <= 5; ++k) fellSchedule.record(0.92 * (1.0 + 0.001 * (k % 2)), 30 + 5 * k);
    EXPECT_EQ(fellSchedule.probation(), StepSchedule::Verdict::NoGain);
    // With every halving spent, a fall and a rise say nothing more: no gain.
    ScheduleState spent{.halvings = StepSchedule::kMaxHalvings};
    StepSchedule spentSchedule(spent);
    for (size_t k = 0; k < fellLosses.size(); ++k) spentSchedule.record(fellLosses[k], 5 * int(k));
    EXPECT_EQ(spentSchedule.probation(), StepSchedule::Verdict::NoGain);
}

// Heights baked as they join (ScheduleState::probationStopsOnlyARise): a start that lies flat
// goes on, as the relief creased cube's did before it fell 9 %; one the steps clearly make worse
// stops, as the relief Spot's at 100 KB (the measured ratios to their starts).
// The verdict of a probation of `state`'s kind on `losses`, measured `every` steps apart.
StepSchedule::Verdict probationVerdict(ScheduleState state, const std::vector<double>& losses, int every) {
    StepSchedule schedule(state);
    for (size_t k = 0; k < losses.size(); ++k) schedule.record(losses[k], every * int(k));
    return schedule.probation();
}

TEST(StepSchedule, AProbationThatStopsOnlyARiseLetsAFlatStartGoOn) {
    auto verdict = [](const std::vector<double>& losses) {
        return probationVerdict({.probationStopsOnlyARise = true}, losses, 5);
    };
    EXPECT_EQ(verdict({1.0, 1.0002, 1.0007, 1.0001, 1.0009, 1.0004}), StepSchedule::Verdict::Paying);  // flat
    EXPECT_EQ(verdict({1.0, 0.998, 0.994, 0.99, 0.985, 0.98}), StepSchedule::Verdict::Paying);         // falling
    EXPECT_EQ(verdict({1.0, 1.0015, 1.003, 1.012, 1.02, 1.027}), StepSchedule::Verdict::NoGain);       // rising
    // A fall and a rise back, which the full probation halves for, is not a clear rise here.
    EXPECT_EQ(verdict({1.0, 0.97, 0.99, 1.0, 1.005, 1.004}), StepSchedule::Verdict::Paying);
}

// The later probation of heights that passed the one above (ScheduleState::probationAsksAGain):
// by then a stage pays if its last window lies below its start, or is falling; one whose
// loss stayed flat or crept up stops (the relief Spot at 50 KB, its losses' ratios to the start).
TEST(StepSchedule, ALaterProbationAsksTheHeightsForAGain) {
    auto verdict = [](const std::vector<double>& losses) {
        return probationVerdict({.probationAsksAGain = true}, losses, 10);
    };
    // Nine measurements: one short of a window, which the schedule would judge (and halve) itself.
    const std::vector<double> crept{1.0, 1.0004, 0.9991, 1.0, 0.9998, 1.0009, 1.0022, 1.0029, 1.0007};
    EXPECT_EQ(verdict(crept), StepSchedule::Verdict::NoGain);
    EXPECT_EQ(verdict({1.0, 1.0, 1.0001, 0.9999, 1.0, 1.0001, 1.0, 0.9999, 1.0}), StepSchedule::Verdict::NoGain);
    // Flat, then falling 2.5 % (the relief creased cube's heights): their best is below the start.
    EXPECT_EQ(verdict({1.0, 1.0, 1.001, 0.999, 0.995, 0.99, 0.985, 0.98, 0.975}), StepSchedule::Verdict::Paying);
    // Flat until the last few, which fall: not yet 0.5 % below the start, but falling.
    EXPECT_EQ(verdict({1.0, 1.0005, 1.0, 1.0005, 1.0, 0.999, 0.998, 0.997, 0.9965}), StepSchedule::Verdict::Paying);
    // One early best 1 % below the start, every measurement since creeping above it (the 1M relief
    // at 50 KB): the gain did not hold.
    EXPECT_EQ(verdict({1.0, 0.9902, 0.993, 0.9961, 1.0009, 1.0046, 1.0037, 1.0052, 1.0093}),
              StepSchedule::Verdict::NoGain);
}

// A later probation ends early once the stage's first window of measurements clearly rose (the
// README demo's heights, their monitored losses over the start: up 3.2 % in 60 steps), and
// never on fewer, a flat one or a dip and a return.
TEST(StepSchedule, AClearRiseOverAWindowIsSeenOnceTheWindowIsFull) {
    auto rose = [](const std::vector<double>& losses) {
        ScheduleState state{.probationAsksAGain = true};
        StepSchedule schedule(state);
        for (size_t k = 0; k < losses.size(); ++k) schedule.record(losses[k], 5 * int(k));
        return schedule.clearlyRose();
    };
    const std::vector<double> demo{1.0, 1.0029, 1.0085, 1.0181, 1.0158, 1.0147, 1.0133, 1.0226, 1.0274, 1.0316};
    EXPECT_TRUE(rose(demo));
    EXPECT_FALSE(rose({demo.begin(), demo.end() - 1}));  // one short of a window
    EXPECT_FALSE(rose({1.0, 1.0004, 0.9991, 1.0, 0.9998, 1.0009, 1.0022, 1.0029, 1.0007, 1.0003}));
    // The relief bishop's: a 2 % dip and back to the start.
    EXPECT_FALSE(rose({1.0, 0.9997, 0.9992, 0.9896, 0.9873, 0.9793, 0.9817, 0.9853, 0.9914, 0.9984}));
}

TEST(DeviceDefaults, SoftwareRenderersAreRecognised) {
    EXPECT_FALSE(isHardwareRenderer("llvmpipe (LLVM 15.0.6, 256 bits)"));
    EXPECT_FALSE(isHardwareRenderer("softpipe"));
    EXPECT_FALSE(isHardwareRenderer("Mesa OffScreen (swrast)"));
    EXPECT_TRUE(isHardwareRenderer("NVIDIA H100 80GB HBM3/PCIe/SSE2"));
    EXPECT_TRUE(isHardwareRenderer("AMD Radeon RX 7900 XTX (radeonsi, navi31, LLVM 15.0.7, DRM 3.54)"));
}

TEST(DeviceDefaults, OnlyWhatWasNotGivenIsChosen) {
    FitOptions software;
    EXPECT_NE(resolveDeviceDefaults(software, "llvmpipe (LLVM 15.0.6, 256 bits)"), "");
    EXPECT_EQ(software.views, kSoftwareDefaults.views);
    EXPECT_EQ(software.resolution, kSoftwareDefaults.resolution);
    EXPECT_EQ(software.steps, kSoftwareDefaults.steps);
    EXPECT_GT(software.steps, 500);  // a cap: the plateau schedule ends a converged fit

    FitOptions gpu;
    gpu.steps = 123;
    const std::string said = resolveDeviceDefaults(gpu, "NVIDIA H100");
    EXPECT_NE(said.find("NVIDIA H100 (GPU)"), std::string::npos) << said;
    EXPECT_EQ(gpu.views, kGpuDefaults.views);
    EXPECT_EQ(gpu.resolution, kGpuDefaults.resolution);
    EXPECT_EQ(gpu.steps, 123);

    FitOptions given = gpu;  // everything set: nothing to say
    EXPECT_EQ(resolveDeviceDefaults(given, "NVIDIA H100"), "");
}

TEST(DeviceDefaults, AFitRefusesOptionsNoDeviceChose) {
    FitOptions o;
    o.out = "out";
    EXPECT_NO_THROW(validate(o));
    EXPECT_THROW(resolved(o), OptionError);
    resolveDeviceDefaults(o, "llvmpipe");
    EXPECT_NO_THROW(resolved(o));
}

}  // namespace
}  // namespace subdfit::fit
