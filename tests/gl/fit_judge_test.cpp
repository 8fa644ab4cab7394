// A fit's second opinion (FitHooks::judge): a stage keeps the judge's lowest of the states the
// monitor found best, stops when the judge sees no gain, and runs as without one where the
// judge agrees with the monitor.
#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <string>

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

// A limit-fitted cage moved off by a fifth of an edge: a start the monitor sees gain from.
struct RoomyStart {
    mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.1f, 3, 40);
    mesh::PolygonMesh cage = [&] {
        mesh::PolygonMesh c = simplify::initialCage(reference, {.faces = 200});
        c.positions = noised(c.positions, 0.2f * mesh::meanEdgeLength(c), 5);
        return c;
    }();
};

// A fit of a RoomyStart in a scratch folder of its own.
struct RoomyFit {
    std::filesystem::path dir;
    fit::FitOptions options;
    RoomyStart start;
    fit::FitScene scene;
    RoomyFit(const char* name, int steps)
        : dir(scratchDir(name)),
          options(smallFitOptions(dir, steps)),
          scene(fit::resolved(options), programs(), start.cage, start.reference) {}
    fit::FitRun run() { return fit::FitRun(fit::resolved(options), programs(), scene); }
};

std::vector<std::vector<float>> thetaOf(fit::CageFitter& fitter) {
    std::vector<std::vector<float>> theta;
    for (auto* group : fitter.groups()) theta.push_back(group->read());
    return theta;
}

// A judge that scores the monitor views and keeps the lowest state it saw.
struct LowestOnTheMonitor {
    fit::FitRun& run;
    const fit::FitScene& scene;
    double lowest = INFINITY;
    std::vector<std::vector<float>> theta{};
    double operator()() {
        const double loss = fit::score(run.fitter(), scene.monitor).loss;
        if (loss < lowest) {
            lowest = loss;
            theta = thetaOf(run.fitter());
        }
        return loss;
    }
};

TEST(FitJudge, AJudgeThatSeesNoGainStopsTheStageAtItsStart) {
    RoomyFit f("judge_no_gain", 100);
    fit::FitRun run = f.run();
    const auto startTheta = thetaOf(run.fitter());
    int judgments = 0;
    const fit::FitHooks hooks{.judge = [&] { return double(++judgments); }};  // each later state worse

    EXPECT_EQ(run.runTo(f.options.steps, f.dir / "checkpoint.bin", hooks), fit::StopReason::NoGain);
    EXPECT_LT(run.step(), f.options.steps);
    EXPECT_EQ(judgments, 2);  // the start and the monitor's best, at the end of the probation
    EXPECT_EQ(thetaOf(run.fitter()), startTheta);
    expectNoGlError();
}

TEST(FitJudge, AJudgeThatAgreesWithTheMonitorChangesNothing) {
    RoomyFit f("judge_agrees", 300);
    auto fitted = [&](bool judged, const char* name) {
        fit::FitRun run = f.run();
        int judgments = 0;
        fit::FitHooks hooks;
        if (judged)
            hooks.judge = [&] {
                ++judgments;
                return fit::score(run.fitter(), f.scene.monitor).loss;
            };
        const fit::StopReason stopped = run.run(f.dir / name / "checkpoint.bin", hooks);
        if (judged) {
            EXPECT_GE(judgments, 3);  // the probation's two and at least one more
        }
        return std::tuple{stopped, run.step(), thetaOf(run.fitter())};
    };
    EXPECT_EQ(fitted(true, "judged"), fitted(false, "alone"));
    expectNoGlError();
}

TEST(FitJudge, AStageKeepsTheJudgesLowestAndStopsOnceItRises) {
    RoomyFit f("judge_rises", 600);
    fit::FitRun run = f.run();
    // The monitor's view until step 150; from there every state the judge sees is worse than
    // any before, as an atlas fitting single samples can look to a supersampled eye.
    LowestOnTheMonitor judge{run, f.scene};
    const fit::FitHooks hooks{.judge = [&] { return run.step() >= 150 ? 1.0 + run.step() : judge(); }};

    EXPECT_EQ(run.runTo(f.options.steps, f.dir / "checkpoint.bin", hooks), fit::StopReason::Converged);
    // Within kJudgedWorse judgments of the rise (or sooner, where the monitor stalls first).
    EXPECT_LE(run.step(), 150 + (fit::FitRun::kJudgedWorse + 1) * fit::FitRun::kJudgeEvery);
    ASSERT_FALSE(judge.theta.empty());
    EXPECT_EQ(thetaOf(run.fitter()), judge.theta);
    expectNoGlError();
}

// With a judge (simplify's fits), a stage whose monitored best is kStalledSteps old stops, in
// the best state, and says so; without one the same fit runs on.
TEST(FitJudge, AStageWhoseMonitorStallsStopsAtItsBest) {
    RoomyFit f("judge_stalls", 800);
    fit::FitRun run = f.run();
    LowestOnTheMonitor judge{run, f.scene};
    std::vector<std::string> notes;
    const fit::FitHooks hooks{.note = [&](const std::string& line) { notes.push_back(line); },
                              .judge = std::ref(judge)};

    EXPECT_EQ(run.runTo(f.options.steps, f.dir / "checkpoint.bin", hooks), fit::StopReason::Converged);
    const auto stalled = std::find_if(notes.begin(), notes.end(), [](const std::string& n) {
        return n.find("the monitor's best has not improved in") != std::string::npos;
    });
    ASSERT_NE(stalled, notes.end()) << "the schedule converged first: the case is not exercised";
    EXPECT_GE(std::stoi(stalled->substr(stalled->find(" in ") + 4)), fit::FitRun::kStalledSteps) << *stalled;
    ASSERT_FALSE(judge.theta.empty());
    EXPECT_EQ(thetaOf(run.fitter()), judge.theta);

    fit::FitRun alone = f.run();  // no judge: the schedule alone decides, and runs past it
    const int past = run.step() + 2 * fit::FitRun::kProbationEvery;
    alone.runTo(past, f.dir / "alone" / "checkpoint.bin");
    EXPECT_EQ(alone.step(), past);
    expectNoGlError();
}

// The judge's record is not checkpointed: a run resumed past its probation judges its stage
// afresh, from the stage's start.
TEST(FitJudge, AResumedStageIsJudgedFromItsStart) {
    RoomyFit f("judge_resumed", 600);
    const auto checkpoint = f.dir / "checkpoint.bin";
    std::vector<std::vector<float>> startTheta;
    {
        fit::FitRun first = f.run();
        startTheta = thetaOf(first.fitter());
        first.runTo(200, checkpoint);
    }
    fit::FitRun resumed = f.run();
    ASSERT_TRUE(resumed.resume(checkpoint));
    int judgments = 0;
    const fit::FitHooks hooks{.judge = [&] { return double(++judgments); }};  // each later state worse

    EXPECT_EQ(resumed.runTo(f.options.steps, checkpoint, hooks), fit::StopReason::Converged);
    EXPECT_LT(resumed.step(), 400);
    EXPECT_EQ(thetaOf(resumed.fitter()), startTheta);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
