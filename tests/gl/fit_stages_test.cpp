// The fit's stages: maps joining a converged cage at their full step, and one widened after its
// predecessor converged ending no worse than it began.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <utility>

#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "fit/step_schedule.h"
#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

// Heights on a lumpy sphere's cage: the cage converges, then the heights (frozen cage), then both.
// Each run judges every stage on the full step's windows (setWindowDoublings(0), as simplify
// does), so that its stages converge within these few steps.
fit::FitOptions stagedFit(const std::filesystem::path& dir) {
    fit::FitOptions o;
    o.out = dir;
    o.steps = 1500;
    o.views = 4;
    o.holdoutViews = 1;
    o.resolution = 48;
    o.maps.displacement = true;
    o.mapResolution = 2;
    o.mapsStart = 0.1f;
    return o;
}

fit::FitScene stagedScene(const fit::FitOptions& o) {
    return fit::FitScene(fit::resolved(o), programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(4, 0.15f, 4));
}

TEST(FitStages, AWidenedStageStartsAfterConvergenceAndEndsNoWorse) {
    const auto dir = scratchDir("fit_stages");
    const fit::FitOptions o = stagedFit(dir);
    fit::FitScene scene = stagedScene(o);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    run.setWindowDoublings(0);

    // The heights alone once the maps join; the cage is let back in when they have converged.
    auto& fitter = run.fitter();
    int widenedAt = -1;
    double lossWhenWidened = 0.0;
    const auto stopped = run.run(
        dir / "checkpoint.bin", {}, [&](bool) { fitter.setOptimised(fitter.vertexGroup(), false); },
        [&] {
            widenedAt = run.step();
            lossWhenWidened = fit::score(fitter, scene.monitor).loss;
            fitter.setOptimised(fitter.vertexGroup(), true);
            return true;
        });
    EXPECT_NE(stopped, fit::StopReason::Cancelled);
    ASSERT_GT(widenedAt, fitter.mapsStartStep()) << "the heights' stage never converged";
    EXPECT_LT(widenedAt, o.steps);
    EXPECT_GT(run.step(), widenedAt);
    EXPECT_LE(fit::score(fitter, scene.monitor).loss, lossWhenWidened);
    expectNoGlError();
}

// Maps that join a cage which converged before their planned start begin at the full step, with
// every halving still theirs to take; the cage keeps the step its halvings reached.
TEST(FitStages, MapsJoiningAConvergedCageStartAtTheFullStep) {
    const auto dir = scratchDir("fit_stages_join");
    fit::FitOptions o = stagedFit(dir);
    o.mapsStart = 0.9f;
    fit::FitScene scene = stagedScene(o);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    run.setWindowDoublings(0);
    auto& fitter = run.fitter();
    std::atomic<bool> cancel{false};
    float mapsScale = 0.0f, cageFactor = 0.0f;
    int joinedAt = -1;
    run.run(dir / "checkpoint.bin", {.cancel = &cancel}, [&](bool) {
        joinedAt = run.step();
        mapsScale = fitter.learningRateScale();
        cageFactor = fitter.vertexRateFactor();
        cancel = true;
    });
    ASSERT_GE(joinedAt, 0);
    ASSERT_LT(joinedAt, int(0.9f * float(o.steps))) << "the cage did not converge before the maps' planned start";
    EXPECT_EQ(mapsScale, 1.0f);
    EXPECT_EQ(cageFactor, std::ldexp(1.0f, -fit::StepSchedule::kMaxHalvings));
    expectNoGlError();
}

// Interrupted inside the widened stage (at its first step: a stage whose probation finds no
// gain may last only a few), a resumed run widens again and ends where a straight run does.
TEST(FitStages, AResumedWidenedStageEndsWhereAStraightRunDoes) {
    const auto dir = scratchDir("fit_stages_resume");
    const fit::FitOptions o = stagedFit(dir);
    fit::FitScene scene = stagedScene(o);
    int widenedAt = -1;
    auto fit = [&](const std::filesystem::path& checkpoint, bool resume, const fit::FitHooks& hooks,
                   std::atomic<bool>* cancelWhenWidened = nullptr) {
        auto run = std::make_unique<fit::FitRun>(fit::resolved(o), programs(), scene);
        run->setWindowDoublings(0);
        if (resume) {
            EXPECT_TRUE(run->resume(checkpoint));
        }
        auto& fitter = run->fitter();
        const auto stopped = run->run(
            checkpoint, hooks, [&](bool) { fitter.setOptimised(fitter.vertexGroup(), false); },
            [&, r = run.get()] {
                widenedAt = r->step();
                fitter.setOptimised(fitter.vertexGroup(), true);
                if (cancelWhenWidened) *cancelWhenWidened = true;
                return true;
            });
        return std::make_pair(stopped, std::move(run));
    };
    auto [straightStop, straight] = fit(dir / "straight.bin", false, {});
    ASSERT_GT(widenedAt, 0);
    const int straightWidenedAt = std::exchange(widenedAt, -1);

    std::atomic<bool> cancel{false};
    auto [interruptedStop, interrupted] = fit(dir / "resumed.bin", false, {.cancel = &cancel}, &cancel);
    ASSERT_EQ(interruptedStop, fit::StopReason::Cancelled);
    EXPECT_EQ(widenedAt, straightWidenedAt);
    auto [resumedStop, resumed] = fit(dir / "resumed.bin", true, {});
    EXPECT_EQ(resumedStop, straightStop);
    EXPECT_EQ(resumed->step(), straight->step());
    EXPECT_EQ(resumed->fitter().vertices(), straight->fitter().vertices());
    EXPECT_EQ(resumed->fitter().maps()->displacement()->theta.read<float>(),
              straight->fitter().maps()->displacement()->theta.read<float>());
    expectNoGlError();
}

// A fit without maps has no maps' stage to widen: it stops, and a start it cannot improve on
// stops on probation.
TEST(FitStages, AFitWithoutMapsIsNeverWidened) {
    const auto dir = scratchDir("fit_stages_bare");
    fit::FitOptions o = stagedFit(dir);
    o.maps = {};
    // The cage's own limit surface: it starts converged, so the schedule stops it after its
    // halvings on any CPU (llvmpipe's arithmetic differs between CPUs, and the lumpy sphere
    // converged past step 1 500 on some).
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    fit::FitScene scene(fit::resolved(o), programs(), cage, surface::limitMesh(cage, 8));
    fit::FitRun run(fit::resolved(o), programs(), scene);
    run.setWindowDoublings(0);
    bool widened = false;
    const auto stopped = run.run(dir / "checkpoint.bin", {}, {}, [&] { return widened = true; });
    EXPECT_EQ(stopped, fit::StopReason::NoGain);
    EXPECT_LT(run.step(), o.steps);
    EXPECT_FALSE(widened);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
