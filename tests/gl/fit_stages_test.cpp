// The fit's stages: one widened after its predecessor converged ends no worse than it began.
#include <gtest/gtest.h>

#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

TEST(FitStages, AWidenedStageStartsAfterConvergenceAndEndsNoWorse) {
    const auto dir = scratchDir("fit_stages");
    fit::FitOptions o;
    o.out = dir;
    o.steps = 1500;
    o.views = 4;
    o.holdoutViews = 1;
    o.resolution = 48;
    o.maps.displacement = true;
    o.mapResolution = 2;
    o.mapsStart = 0.1f;
    fit::FitScene scene(o, programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(4, 0.15f, 4));
    fit::FitRun run(o, programs(), scene);

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

// A fit without maps has no maps' stage to widen: it converges and stops.
TEST(FitStages, AFitWithoutMapsIsNeverWidened) {
    const auto dir = scratchDir("fit_stages_bare");
    fit::FitOptions o;
    o.out = dir;
    o.steps = 1500;
    o.views = 4;
    o.holdoutViews = 1;
    o.resolution = 48;
    fit::FitScene scene(o, programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(4, 0.15f, 4));
    fit::FitRun run(o, programs(), scene);
    bool widened = false;
    const auto stopped = run.run(dir / "checkpoint.bin", {}, {}, [&] { return widened = true; });
    EXPECT_EQ(stopped, fit::StopReason::Converged);
    EXPECT_LT(run.step(), o.steps);
    EXPECT_FALSE(widened);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
