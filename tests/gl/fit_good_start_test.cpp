// A fit from a good start: it never ends below where it began, it still gains where the start
// leaves room, and a default fit that is still improving is not cut off at a fixed step count.
#include <gtest/gtest.h>

#include "fit/device_defaults.h"
#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "simplify/cage/initial_cage.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

fit::FitOptions smallFit(const std::filesystem::path& dir) { return smallFitOptions(dir, 100); }

// A dense reference and the cage simplify starts from: limit-fitted to it, already close.
struct GoodStart {
    mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.1f, 3, 40);
    mesh::PolygonMesh cage = simplify::initialCage(reference, {.faces = 200});
};

TEST(FitFromAGoodStart, NeverEndsBelowItsStart) {
    const auto dir = scratchDir("good_start");
    const fit::FitOptions o = smallFit(dir);
    const GoodStart start;
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    const auto monitorBefore = fit::score(run.fitter(), scene.monitor);
    const auto holdoutBefore = fit::score(run.fitter(), scene.holdout);
    const auto stopped = run.run(dir / "checkpoint.bin");
    EXPECT_NE(stopped, fit::StopReason::Cancelled);
    EXPECT_LE(fit::score(run.fitter(), scene.monitor).loss, monitorBefore.loss);
    // The held-out views are not the ones the fit kept its best state by: a hair's breadth.
    EXPECT_GE(fit::score(run.fitter(), scene.holdout).psnr, holdoutBefore.psnr - 0.05);
    expectNoGlError();
}

TEST(FitFromAGoodStart, GainsWhereTheStartLeavesRoom) {
    const auto dir = scratchDir("good_start_room");
    const fit::FitOptions o = smallFit(dir);
    GoodStart start;
    // The same cage, its vertices moved off by a fifth of an edge: room the images can see.
    start.cage.positions = noised(start.cage.positions, 0.2f * mesh::meanEdgeLength(start.cage), 5);
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    const double before = fit::score(run.fitter(), scene.monitor).loss;
    const auto stopped = run.run(dir / "checkpoint.bin");
    EXPECT_NE(stopped, fit::StopReason::NoGain);
    EXPECT_LT(fit::score(run.fitter(), scene.monitor).loss, 0.8 * before);
    expectNoGlError();
}

// Simplify reads only the held-out scores: a run that skips the training views' scores reports
// the same held-out scores, before and after, as one that takes them, and no training ones.
TEST(FitFromAGoodStart, HoldoutOnlyScoresMatchAFullScoring) {
    const auto dir = scratchDir("holdout_only");
    fit::FitOptions o = smallFit(dir);
    GoodStart start;
    start.cage.positions = noised(start.cage.positions, 0.2f * mesh::meanEdgeLength(start.cage), 5);
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    auto reportOf = [&](fit::ReportScores scores, const char* name) {
        fit::FitRun run(fit::resolved(o), programs(), scene, scores);
        run.runTo(15, dir / name / "checkpoint.bin");
        return run.writeResults(dir / name, glContext());
    };
    const fit::FitReport full = reportOf(fit::ReportScores::TrainingAndHoldout, "full");
    const fit::FitReport holdout = reportOf(fit::ReportScores::HoldoutOnly, "holdout");
    ASSERT_TRUE(full.trainBefore && full.trainAfter);
    EXPECT_NE(full.trainAfter->loss, full.trainBefore->loss);  // the fit moved: "after" was drawn again
    EXPECT_FALSE(holdout.trainBefore || holdout.trainAfter);
    EXPECT_FALSE(fit::toJson(holdout).contains("loss_final"));
    EXPECT_EQ(holdout.holdoutBefore.psnrViews, full.holdoutBefore.psnrViews);
    EXPECT_EQ(holdout.holdoutAfter.psnrViews, full.holdoutAfter.psnrViews);
    EXPECT_EQ(holdout.holdoutAfter.ssim, full.holdoutAfter.ssim);
    expectNoGlError();
}

// render() evaluates a θ's points once for all the views it is drawn on: once the vertices have
// moved (here written from outside), it draws them where they are now, as a fresh fitter does.
TEST(FitFromAGoodStart, RenderDrawsMovedVerticesWhereTheyAre) {
    const auto dir = scratchDir("render_moved");
    const fit::FitOptions o = smallFit(dir);
    const GoodStart start;
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    fit::CageFitter fitter(programs(), scene.cage, fit::fitSettings(o, scene.cage, scene.shading));
    auto drawn = [&](fit::CageFitter& f) {
        return scene.monitor.render(
            0, [&](const render::Camera& camera, const render::RenderTarget& canvas) { f.render(camera, canvas); });
    };
    const auto before = drawn(fitter);
    EXPECT_EQ(drawn(fitter), before);  // drawn again from the points evaluated once
    mesh::PolygonMesh moved = scene.cage;
    moved.positions = noised(moved.positions, 0.2f * mesh::meanEdgeLength(moved), 5);
    fitter.setVertices(moved.positions);
    fit::CageFitter fresh(programs(), moved, fit::fitSettings(o, moved, scene.shading));
    const auto after = drawn(fitter);
    EXPECT_NE(after, before);
    EXPECT_EQ(after, drawn(fresh));
    expectNoGlError();
}

// The default step bound is a generous cap, not a fixed 500: a fit still improving there goes on.
TEST(FitFromAGoodStart, ADefaultFitStillImprovingAt500StepsGoesOn) {
    const auto dir = scratchDir("default_bound");
    fit::FitOptions o = smallFit(dir);
    o.steps = fit::kByDevice;
    o.resolution = 32;
    o.views = 4;
    o.learningRate = 0.01f;  // a slow fit, so that 500 steps leave it improving
    fit::resolveForCurrentDevice(o);
    ASSERT_GT(o.steps, 500);
    mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    for (auto& p : cage.positions) p *= 0.6f;
    fit::FitScene scene(fit::resolved(o), programs(), cage, mesh::makeLumpySphere(4, 0.1f, 2));
    fit::FitRun run(fit::resolved(o), programs(), scene);
    run.runTo(400, dir / "checkpoint.bin");
    const double at400 = fit::score(run.fitter(), scene.monitor).loss;
    run.runTo(500, dir / "checkpoint.bin");
    ASSERT_LT(fit::score(run.fitter(), scene.monitor).loss, 0.98 * at400) << "not improving at 500 steps";
    EXPECT_FALSE(run.done());
    EXPECT_EQ(run.stopReason(), fit::StopReason::Reached);
    run.runTo(600, dir / "checkpoint.bin");
    EXPECT_EQ(run.step(), 600);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
