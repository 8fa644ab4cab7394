// The knobs an interactive run turns between steps (the viewer's panel): groups left out of the
// turns keep their parameters, and rates set by hand are the ones the passes use.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <utility>

#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"

namespace subdfit::test {
namespace {

fit::CageFitSettings withDisplacement() {
    fit::CageFitSettings settings;
    settings.resolution = 48;
    settings.mapEffects.set(maps::MapKind::Displacement);
    settings.maps.resolution = 2;
    return settings;
}

TEST(FitKnobs, AGroupLeftOutKeepsItsParameters) {
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(3, 0.2f, 3), 2, 48);
    auto settings = withDisplacement();
    settings.plannedSteps = 100;  // the maps would join only after 40 steps
    fit::CageFitter fitter(programs(), scene.cage, settings);
    auto& vertices = fitter.vertexGroup();
    auto& displacement = *fitter.maps()->displacement();
    const auto verticesBefore = vertices.read();
    const auto displacementBefore = displacement.read();

    // Vertices out: the displacement takes every turn, also before its planned start.
    fitter.setOptimised(vertices, false);
    EXPECT_FALSE(fitter.optimised(vertices));
    const int views[] = {0, 1};
    for (int k = 0; k < 4; ++k) fitter.step(*scene.targets, views);
    EXPECT_EQ(vertices.read(), verticesBefore);
    EXPECT_NE(displacement.read(), displacementBefore);

    // Everything out: a step changes nothing.
    fitter.setOptimised(displacement, false);
    const auto displacementFrozen = displacement.read();
    fitter.step(*scene.targets, views);
    EXPECT_EQ(vertices.read(), verticesBefore);
    EXPECT_EQ(displacement.read(), displacementFrozen);

    // Back in: the vertices move again.
    fitter.setOptimised(vertices, true);
    fitter.step(*scene.targets, views);
    EXPECT_NE(vertices.read(), verticesBefore);
}

TEST(FitKnobs, RatesSetByHandAreUsed) {
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(3, 0.2f, 3), 1, 48);
    fit::CageFitter fitter(programs(), scene.cage, withDisplacement());
    auto& vertices = fitter.vertexGroup();
    auto& displacement = *fitter.maps()->displacement();
    fitter.setRates(vertices, 0.02f, 0.01f);
    fitter.setRates(displacement, 0.003f, 0.002f);
    EXPECT_EQ(vertices.settings().epsilon, 0.02f);
    EXPECT_EQ(vertices.settings().learningRate, 0.01f);
    EXPECT_EQ(displacement.settings().epsilon, 0.003f);
    EXPECT_EQ(displacement.settings().learningRate, 0.002f);
    // No planned steps, no annealing: the rate Adam is given is the one set, and a step leaves
    // the group's settings (the one source of its rates) as they were.
    EXPECT_EQ(fitter.learningRateScale(), 1.0f);
    const int views[] = {0};
    fitter.step(*scene.targets, views);
    EXPECT_EQ(vertices.settings().learningRate, 0.01f);
    EXPECT_EQ(displacement.settings().learningRate, 0.002f);
}

// A map's turn draws the cage and the heights as they were at the last such turn without
// evaluating them again while they stay (the normal map alone taking the turns here). Written
// from outside in between (setVertices, a group's write, a restored state), the next turn must
// draw them as they are now: its loss is that of a fitter built on the state just written.
TEST(FitKnobs, AMapTurnDrawsTheCageAndHeightsAsTheyAreNow) {
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(2), mesh::makeLumpySphere(3, 0.2f, 3), 1, 64);
    auto settings = withDisplacement();
    settings.resolution = 64;
    settings.mapEffects.set(maps::MapKind::NormalMap);
    auto frozenButTheNormals = [](fit::CageFitter& f) {
        f.setOptimised(f.vertexGroup(), false);
        f.setOptimised(*f.maps()->displacement(), false);
    };
    fit::CageFitter fitter(programs(), scene.cage, settings);
    frozenButTheNormals(fitter);
    const int views[] = {0};
    for (int k = 0; k < 3; ++k) fitter.step(*scene.targets, views, false);
    const auto earlier = fitter.state();
    fitter.step(*scene.targets, views, false);

    auto moved = fitter.vertices();
    for (auto& p : moved) p *= 1.05f;
    auto heights = fitter.maps()->displacement()->read();
    for (float& h : heights) h += 0.02f;
    const std::pair<const char*, std::function<void()>> writes[] = {
        {"setVertices", [&] { fitter.setVertices(moved); }},
        {"the heights' write", [&] { fitter.maps()->displacement()->write(heights); }},
        {"restore", [&] { fitter.restore(earlier); }}};
    for (const auto& [what, write] : writes) {
        fitter.accumulate(*scene.targets, views, true);
        const float before = fitter.takeMeanLoss();
        fitter.update();
        write();
        fit::CageFitter fresh(programs(), scene.cage, settings);
        frozenButTheNormals(fresh);
        fresh.restore(fitter.state());
        fitter.accumulate(*scene.targets, views, true);
        fresh.accumulate(*scene.targets, views, true);
        const float after = fitter.takeMeanLoss(), expected = fresh.takeMeanLoss();
        // The loss slots are float sums whose order the threads set: equal to a few ulps.
        EXPECT_NEAR(after, expected, 1e-5f * expected) << what;
        EXPECT_GT(std::abs(after - before), 1e-3f * expected) << what << ": the write shows in the loss";
        fitter.update();
    }
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
