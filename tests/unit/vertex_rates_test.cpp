// The vertex ε and learning rate a fit records: options count them in fractions of the cage's
// mean edge, the fitter's group in scene units; what a viewer's knob set must go back as a
// fraction (report.json's settings mean one thing, whoever saved them).
#include <gtest/gtest.h>

#include "fit/fit_scene.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"

namespace subdfit::fit {
namespace {

FitOptions resolvedOptions() {
    FitOptions o;
    o.resolution = 64;
    o.views = 4;
    o.steps = 10;
    return o;
}

TEST(VertexRates, HandSetRatesGoBackAsFractionsOfTheMeanEdge) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(6);
    const FitOptions options = resolvedOptions();
    optim::GroupSettings knobs = fitSettings(options, cage).vertices;
    knobs.epsilon *= 0.5f;
    knobs.learningRate *= 0.25f;
    const FitOptions saved = withVertexRates(options, cage, knobs);
    const float edge = mesh::meanEdgeLength(cage);
    EXPECT_FLOAT_EQ(saved.epsilon, knobs.epsilon / edge);
    EXPECT_FLOAT_EQ(saved.learningRate, knobs.learningRate / edge);
    // Read back as a command line would: the same knobs again.
    const optim::GroupSettings again = fitSettings(saved, cage).vertices;
    EXPECT_FLOAT_EQ(again.epsilon, knobs.epsilon);
    EXPECT_FLOAT_EQ(again.learningRate, knobs.learningRate);
}

TEST(VertexRates, RatesTheOptionsGaveStayAsGiven) {
    // At 64² the pixel caps bind on this cage: the group holds the cap, not epsilon · edge.
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(6);
    const FitOptions options = resolvedOptions();
    const optim::GroupSettings given = fitSettings(options, cage).vertices;
    ASSERT_LT(given.epsilon, options.epsilon * mesh::meanEdgeLength(cage));
    const FitOptions saved = withVertexRates(options, cage, given);
    EXPECT_EQ(saved.epsilon, options.epsilon);
    EXPECT_EQ(saved.learningRate, options.learningRate);
}

}  // namespace
}  // namespace subdfit::fit
