// How long a fit runs and with what: the plateau schedule's decisions, and the options a device
// chooses when the user did not.
#include <gtest/gtest.h>

#include <cmath>

#include "fit/device_defaults.h"
#include "fit/step_schedule.h"

namespace subdfit::fit {
namespace {

TEST(StepSchedule, KeepsTheFullStepWhileTheLossFallsAndRemembersTheBest) {
    ScheduleState state;
    StepSchedule schedule(state);
    double loss = 1.0;
    for (int k = 0; k < 20; ++k, loss *= 0.9) {
        const auto decision = schedule.record(loss, 10 * k);
        EXPECT_TRUE(decision.best);
        EXPECT_EQ(decision.action, StepSchedule::Action::Continue);
    }
    EXPECT_EQ(state.halvings, 0);
    EXPECT_EQ(state.bestStep, 190);
    EXPECT_FLOAT_EQ(schedule.learningRateScale(), 1.0f);
}

TEST(StepSchedule, HalvesOnAPlateauThenConverges) {
    ScheduleState state;
    StepSchedule schedule(state);
    schedule.record(1.0, 0);
    int halvings = 0, measurements = 0;
    StepSchedule::Action action = StepSchedule::Action::Continue;
    // A loss that no longer improves (a worse one is never "best").
    while (action != StepSchedule::Action::Converged && measurements < 100) {
        const double loss = 1.0 + 0.01 * (measurements % 3);
        action = schedule.record(loss, ++measurements).action;
        if (action == StepSchedule::Action::Halve) ++halvings;
    }
    EXPECT_EQ(action, StepSchedule::Action::Converged);
    EXPECT_EQ(halvings, StepSchedule::kMaxHalvings);
    EXPECT_EQ(measurements, StepSchedule::kPatience * (StepSchedule::kMaxHalvings + 1));
    EXPECT_FLOAT_EQ(schedule.learningRateScale(), 1.0f / 8.0f);
    EXPECT_EQ(state.bestStep, 0);  // nothing after the start was better
}

TEST(StepSchedule, SmallGainsDoNotResetThePatienceButAreKept) {
    ScheduleState state;
    StepSchedule schedule(state);
    schedule.record(1.0, 0);
    double loss = 1.0;
    StepSchedule::Action action = StepSchedule::Action::Continue;
    for (int k = 1; k <= StepSchedule::kPatience; ++k) {
        loss *= 1.0 - StepSchedule::kMinImprovement / 4;  // better, but not significantly
        const auto decision = schedule.record(loss, k);
        EXPECT_TRUE(decision.best);
        action = decision.action;
    }
    EXPECT_EQ(action, StepSchedule::Action::Halve);
    EXPECT_EQ(state.bestStep, StepSchedule::kPatience);
}

TEST(StepSchedule, ANonFiniteLossIsNeverTheBest) {
    ScheduleState state;
    StepSchedule schedule(state);
    schedule.record(1.0, 0);
    EXPECT_FALSE(schedule.record(std::nan(""), 1).best);
    EXPECT_EQ(state.bestStep, 0);
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
    EXPECT_THROW(validateResolved(o), OptionError);
    resolveDeviceDefaults(o, "llvmpipe");
    EXPECT_NO_THROW(validateResolved(o));
}

}  // namespace
}  // namespace subdfit::fit
