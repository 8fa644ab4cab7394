// The fit's stages: maps joining a converged cage at their full step, a run interrupted as they
// join ending where a straight run does, and a fit without maps stopping on its probation.
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
    o.maps.set(maps::MapKind::Displacement);
    o.mapResolution = 2;
    o.mapsStart = 0.1f;
    return o;
}

fit::FitScene stagedScene(const fit::FitOptions& o) {
    return fit::FitScene(fit::resolved(o), programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(4, 0.15f, 4));
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
    // Observed as the maps join: their start leaves them as they are.
    run.run(dir / "checkpoint.bin", {.cancel = &cancel}, {.startFrom = [&](const mesh::PolygonMesh&) {
                joinedAt = run.step();
                mapsScale = fitter.learningRateScale();
                cageFactor = fitter.vertexRateFactor();
                cancel = true;
                return surface::SurfaceMaps{};
            }});
    ASSERT_GE(joinedAt, 0);
    ASSERT_LT(joinedAt, int(0.9f * float(o.steps))) << "the cage did not converge before the maps' planned start";
    EXPECT_EQ(mapsScale, 1.0f);
    EXPECT_EQ(cageFactor, std::ldexp(1.0f, -fit::StepSchedule::kMaxHalvings));
    expectNoGlError();
}

// Interrupted as the maps join (the cage frozen by their stage), a resumed run freezes it again and
// ends where a straight run does.
TEST(FitStages, ARunInterruptedAsTheMapsJoinEndsWhereAStraightRunDoes) {
    const auto dir = scratchDir("fit_stages_resume");
    const fit::FitOptions o = stagedFit(dir);
    fit::FitScene scene = stagedScene(o);
    int joinedAt = -1;
    auto fit = [&](const std::filesystem::path& checkpoint, bool resume, const fit::FitHooks& hooks,
                   std::atomic<bool>* cancelWhenJoined = nullptr) {
        auto run = std::make_unique<fit::FitRun>(fit::resolved(o), programs(), scene);
        run->setWindowDoublings(0);
        if (resume) {
            EXPECT_TRUE(run->resume(checkpoint));
        }
        fit::MapStage stage{.startFrom =
                                [&, r = run.get()](const mesh::PolygonMesh&) {
                                    joinedAt = r->step();
                                    if (cancelWhenJoined) *cancelWhenJoined = true;
                                    return surface::SurfaceMaps{};
                                },
                            .freezeCage = true};
        const auto stopped = run->run(checkpoint, hooks, stage);
        return std::make_pair(stopped, std::move(run));
    };
    auto [straightStop, straight] = fit(dir / "straight.bin", false, {});
    ASSERT_GT(joinedAt, 0);
    const int straightJoinedAt = std::exchange(joinedAt, -1);

    std::atomic<bool> cancel{false};
    auto [interruptedStop, interrupted] = fit(dir / "resumed.bin", false, {.cancel = &cancel}, &cancel);
    ASSERT_EQ(interruptedStop, fit::StopReason::Cancelled);
    EXPECT_EQ(joinedAt, straightJoinedAt);
    auto [resumedStop, resumed] = fit(dir / "resumed.bin", true, {});
    EXPECT_EQ(resumedStop, straightStop);
    EXPECT_EQ(resumed->step(), straight->step());
    EXPECT_EQ(resumed->fitter().vertices(), straight->fitter().vertices());
    EXPECT_EQ(resumed->fitter().maps()->displacement()->theta.read<float>(),
              straight->fitter().maps()->displacement()->theta.read<float>());
    expectNoGlError();
}

// A fit without maps is one stage: a start it cannot improve on stops on its probation.
TEST(FitStages, AFitWithoutMapsStopsOnItsProbation) {
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
    bool mapsStarted = false;
    const auto stopped = run.run(dir / "checkpoint.bin", {}, {.startFrom = [&](const mesh::PolygonMesh&) {
                                     mapsStarted = true;
                                     return surface::SurfaceMaps{};
                                 }});
    EXPECT_EQ(stopped, fit::StopReason::NoGain);
    EXPECT_LT(run.step(), o.steps);
    EXPECT_FALSE(mapsStarted);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
