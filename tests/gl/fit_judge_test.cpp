// A fit's second opinion (FitHooks::judge): a stage keeps the judge's lowest of the states the
// monitor found best, stops when the judge sees no gain, and runs as without one where the
// judge agrees with the monitor.
#include <gtest/gtest.h>

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

fit::FitOptions smallFit(const std::filesystem::path& dir, int steps) {
    fit::FitOptions o;
    o.out = dir;
    o.steps = steps;
    o.views = 6;
    o.holdoutViews = 2;
    o.resolution = 48;
    return o;
}

// A limit-fitted cage moved off by a fifth of an edge: a start the monitor sees gain from.
struct RoomyStart {
    mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.1f, 3, 40);
    mesh::PolygonMesh cage = [&] {
        mesh::PolygonMesh c = simplify::initialCage(reference, {.faces = 200});
        c.positions = noised(c.positions, 0.2f * mesh::meanEdgeLength(c), 5);
        return c;
    }();
};

std::vector<std::vector<float>> thetaOf(fit::CageFitter& fitter) {
    std::vector<std::vector<float>> theta;
    for (auto* group : fitter.groups()) theta.push_back(group->read());
    return theta;
}

TEST(FitJudge, AJudgeThatSeesNoGainStopsTheStageAtItsStart) {
    const auto dir = scratchDir("judge_no_gain");
    const fit::FitOptions o = smallFit(dir, 100);
    const RoomyStart start;
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    const auto startTheta = thetaOf(run.fitter());
    int judgments = 0;
    const fit::FitHooks hooks{.judge = [&] { return double(++judgments); }};  // each later state worse

    EXPECT_EQ(run.runTo(o.steps, dir / "checkpoint.bin", hooks), fit::StopReason::NoGain);
    EXPECT_LT(run.step(), o.steps);
    EXPECT_EQ(judgments, 2);  // the start and the monitor's best, at the end of the probation
    EXPECT_EQ(thetaOf(run.fitter()), startTheta);
    expectNoGlError();
}

TEST(FitJudge, AJudgeThatAgreesWithTheMonitorChangesNothing) {
    const auto dir = scratchDir("judge_agrees");
    const fit::FitOptions o = smallFit(dir, 300);
    const RoomyStart start;
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    auto fitted = [&](bool judged, const char* name) {
        fit::FitRun run(fit::resolved(o), programs(), scene);
        int judgments = 0;
        fit::FitHooks hooks;
        if (judged)
            hooks.judge = [&] {
                ++judgments;
                return fit::score(run.fitter(), scene.monitor).loss;
            };
        const fit::StopReason stopped = run.run(dir / name / "checkpoint.bin", hooks);
        if (judged) EXPECT_GE(judgments, 3);  // the probation's two and at least one more
        return std::tuple{stopped, run.step(), thetaOf(run.fitter())};
    };
    EXPECT_EQ(fitted(true, "judged"), fitted(false, "alone"));
    expectNoGlError();
}

TEST(FitJudge, AStageKeepsTheJudgesLowestAndStopsOnceItRises) {
    const auto dir = scratchDir("judge_rises");
    const fit::FitOptions o = smallFit(dir, 600);
    const RoomyStart start;
    fit::FitScene scene(fit::resolved(o), programs(), start.cage, start.reference);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    // The monitor's view until step 150; from there every state the judge sees is worse than
    // any before, as an atlas fitting single samples can look to a supersampled eye.
    double lowest = INFINITY;
    std::vector<std::vector<float>> lowestTheta;
    const fit::FitHooks hooks{.judge = [&] {
        if (run.step() >= 150) return 1.0 + run.step();
        const double loss = fit::score(run.fitter(), scene.monitor).loss;
        if (loss < lowest) {
            lowest = loss;
            lowestTheta = thetaOf(run.fitter());
        }
        return loss;
    }};

    EXPECT_EQ(run.runTo(o.steps, dir / "checkpoint.bin", hooks), fit::StopReason::Converged);
    EXPECT_LT(run.step(), o.steps);
    EXPECT_GE(run.step(), 150 + fit::FitRun::kJudgedWorse * fit::FitRun::kJudgeEvery - fit::FitRun::kJudgeEvery);
    ASSERT_FALSE(lowestTheta.empty());
    EXPECT_EQ(thetaOf(run.fitter()), lowestTheta);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
