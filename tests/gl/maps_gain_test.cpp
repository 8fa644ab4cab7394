// What the displacement map buys: on a reference whose relief a coarse cage cannot hold, a fit
// with the map ends closer to it on held-out views than a vertex-only fit with the same steps.
#include <gtest/gtest.h>

#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

double heldOutLoss(const std::string& name, maps::MapEffects effects, std::uint32_t seed) {
    fit::FitOptions o;
    o.out = scratchDir(name);
    o.steps = 240;
    o.seed = seed;
    o.views = 6;
    o.holdoutViews = 3;
    o.resolution = 96;
    o.maps = effects;
    o.mapResolution = 8;
    o.mapsStart = 0.1f;  // what the map buys, given the steps to buy it
    // 96 quads under 80 small bumps: the cage can round the sphere, not raise the bumps. A map
    // cell spans about two pixels.
    fit::FitScene scene(fit::resolved(o), programs(), mesh::makeQuadSphere(4),
                        mesh::makeLumpySphere(5, 0.05f, 7, 80, 0.005f, 0.015f));
    fit::FitRun run(fit::resolved(o), programs(), scene);
    run.run(o.out / "checkpoint.bin");
    expectNoGlError();
    return fit::score(run.fitter(), scene.holdout).loss;
}

TEST(MapsGain, ADisplacementMapEndsBelowAVertexOnlyFitOnHeldOutViews) {
    // Summed over two seeds: one fit's path is chaotic enough that a rounding difference between
    // CPUs moves its loss by a tenth.
    double vertexOnly = 0.0, displaced = 0.0;
    for (std::uint32_t seed : {1u, 2u}) {
        vertexOnly += heldOutLoss("maps_gain_none", maps::parseMapEffects("none"), seed);
        displaced += heldOutLoss("maps_gain_displacement", maps::parseMapEffects("displacement"), seed);
    }
    // 1.5 dB: the loss at most 0.71 of the vertex-only fit's.
    EXPECT_LT(displaced, 0.71 * vertexOnly) << "vertex-only " << vertexOnly << ", displaced " << displaced;
}

}  // namespace
}  // namespace subdfit::test
