// The knobs an interactive run turns between steps (the viewer's panel): groups left out of the
// turns keep their parameters, and rates set by hand are the ones the passes use.
#include <gtest/gtest.h>

#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"

namespace subdfit::test {
namespace {

fit::CageFitSettings withDisplacement() {
    fit::CageFitSettings settings;
    settings.resolution = 48;
    settings.mapEffects.displacement = true;
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

}  // namespace
}  // namespace subdfit::test
