// The heights fitted as the decoder reads them (fit/coded_refinement.h): the fitter ends holding
// the judged lowest, as fitted, its rates and turns as they were; a budget that admits nothing
// leaves the start.
#include <gtest/gtest.h>

#include "codec/node_coding.h"
#include "fit/coded_refinement.h"
#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/initial_cage.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

constexpr int kBits = 4;

// A 300-face cage of a lumpy sphere with its heights baked at T = 4.
struct BakedHeights {
    std::filesystem::path dir;
    fit::FitOptions options;
    mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.1f, 3, 40);
    mesh::PolygonMesh cage = simplify::initialCage(reference, {.faces = 300});
    fit::FitScene scene;
    fit::FitRun run;
    explicit BakedHeights(const char* name)
        : dir(scratchDir(name)),
          options([&] {
              fit::FitOptions o = smallFitOptions(dir, 100);
              o.maps = {maps::MapKind::Displacement};
              o.mapResolution = 4;
              return o;
          }()),
          scene(fit::resolved(options), programs(), cage, reference),
          run(fit::resolved(options), programs(), scene) {
        run.startFrom(simplify::bakeFor(scene.cage, scene.reference, *run.fitter().maps()));
    }
    // The heights at `fraction` of their bake: a start with room to gain.
    void flatten(float fraction) {
        std::vector<float> values = heights().read();
        for (float& h : values) h *= fraction;
        heights().write(values);
    }
    optim::ParameterGroup& heights() { return *run.fitter().maps()->displacement(); }
    double judge() { return fit::score(run.fitter(), scene.monitor).loss; }
};

TEST(CodedRefinement, EndsAtTheJudgedLowestAsFitted) {
    BakedHeights b("coded_refinement_lowest");
    b.flatten(0.5f);  // many coding steps off: Adam steps of a quarter of one
    fit::CageFitter& fitter = b.run.fitter();
    const optim::GroupSettings rates = b.heights().settings();
    int judgments = 0;
    const fit::CodedRefinement r =
        fit::refineAsCoded(b.run, {.bits = kBits, .steps = 60, .judgeEvery = 20, .stepFraction = 0.25f}, [&] {
            ++judgments;
            return b.judge();
        });
    EXPECT_GT(r.steps, 0);
    EXPECT_EQ(judgments, 1 + r.steps / 20);
    EXPECT_LE(r.bestLoss, r.startLoss);
    EXPECT_EQ(r.overBudget, 0);
    EXPECT_GT(r.bestStep, 0);
    EXPECT_LT(r.bestLoss, r.startLoss);
    // What it holds codes to what was judged lowest.
    const std::vector<float> held = b.heights().read();
    b.heights().write(codec::codedValues(fitter.maps()->layout(), held, 1, kBits));
    EXPECT_DOUBLE_EQ(b.judge(), r.bestLoss);
    EXPECT_EQ(b.heights().settings().learningRate, rates.learningRate);
    EXPECT_TRUE(fitter.optimised(fitter.vertexGroup()));
    expectNoGlError();
}

TEST(CodedRefinement, ABudgetThatAdmitsNothingLeavesTheStart) {
    BakedHeights b("coded_refinement_refused");
    const std::vector<float> start = b.heights().read();
    int asked = 0;
    const fit::CodedRefinement r = fit::refineAsCoded(
        b.run, {.bits = kBits, .steps = 100, .judgeEvery = 10}, [&] { return b.judge(); },
        [&] {
            ++asked;
            return false;
        });
    EXPECT_EQ(r.steps, 20);  // two judgments refused in a row end it
    EXPECT_EQ(r.overBudget, 2);
    EXPECT_GT(asked, 2);  // each refusal bisected towards the start first
    EXPECT_EQ(r.bestStep, 0);
    EXPECT_EQ(b.heights().read(), start);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
