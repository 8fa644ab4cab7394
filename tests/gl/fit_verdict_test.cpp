// simplify's verdict on a fit: the fitted state ships only where it beats, on the choosing views,
// the bake it started from; otherwise the bake is what the fitter holds, exactly.
#include <gtest/gtest.h>

#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/fit_verdict.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

fit::FitOptions smallFit(const std::filesystem::path& dir) {
    fit::FitOptions o = smallFitOptions(dir, 50);
    o.maps = {maps::MapKind::Displacement};
    return o;
}

const mesh::PolygonMesh& reference() {
    static const mesh::PolygonMesh lumpy = mesh::makeLumpySphere(4, 0.1f, 3, 40);
    return lumpy;
}

// A limit-fitted cage, as simplify starts from, its vertices moved off by `offEdges` of an edge.
mesh::PolygonMesh cageOff(float offEdges) {
    mesh::PolygonMesh cage = simplify::initialCage(reference(), {.faces = 200});
    if (offEdges > 0.0f) cage.positions = noised(cage.positions, offEdges * mesh::meanEdgeLength(cage), 5);
    return cage;
}

// The fitter holds exactly `positions` and `heights`, and the verdict's `loss` is theirs.
void expectHolds(fit::CageFitter& fitter, const fit::FitScene& scene, const std::vector<glm::vec3>& positions,
                 const std::vector<float>& heights, double loss) {
    EXPECT_EQ(fitter.vertices(), positions);
    EXPECT_EQ(fitter.maps()->displacement()->read(), heights);
    EXPECT_EQ(fit::score(fitter, scene.choosing(programs())).loss, loss);
    expectNoGlError();
}

TEST(FitVerdict, AFitWorseThanItsBakeLeavesTheBake) {
    const auto dir = scratchDir("fit_verdict_worse");
    const fit::FitOptions o = smallFit(dir);
    fit::FitScene scene(fit::resolved(o), programs(), cageOff(0.0f), reference());
    fit::FitRun run(fit::resolved(o), programs(), scene);
    // A fit gone wrong: its vertices a fifth of an edge off the limit-fitted start.
    fit::CageFitter& fitter = run.fitter();
    fitter.setVertices(noised(scene.cage.positions, 0.2f * mesh::meanEdgeLength(scene.cage), 7));

    const simplify::FitVerdict verdict = simplify::keepTheFitWhereItPays(run, programs());
    EXPECT_FALSE(verdict.fitShips);
    EXPECT_GT(verdict.fittedLoss, verdict.bakedLoss);
    // The fitter holds the bake: the initial cage, its heights baked onto it.
    expectHolds(fitter, scene, scene.cage.positions,
                simplify::bakeFor(scene.cage, scene.reference, *fitter.maps()).displacement, verdict.bakedLoss);
}

TEST(FitVerdict, AFitBetterThanItsBakeShipsAsFitted) {
    const auto dir = scratchDir("fit_verdict_better");
    const fit::FitOptions o = smallFit(dir);
    // The bake's cage is off; the "fitted" state is the limit-fitted cage with its own bake,
    // its heights nudged so that they are not any bake's.
    fit::FitScene scene(fit::resolved(o), programs(), cageOff(0.2f), reference());
    fit::FitRun run(fit::resolved(o), programs(), scene);
    fit::CageFitter& fitter = run.fitter();
    mesh::PolygonMesh good = scene.cage;
    good.positions = scene.frame.toNormalized(cageOff(0.0f).positions);
    fitter.setVertices(good.positions);
    std::vector<float> heights = simplify::bakeFor(good, scene.reference, *fitter.maps()).displacement;
    for (size_t k = 0; k < heights.size(); k += 7) heights[k] *= 0.9f;
    fitter.maps()->displacement()->write(heights);

    const simplify::FitVerdict verdict = simplify::keepTheFitWhereItPays(run, programs());
    EXPECT_TRUE(verdict.fitShips);
    EXPECT_LT(verdict.fittedLoss, verdict.bakedLoss);
    // Exactly the fitted state, not a bake of it.
    expectHolds(fitter, scene, good.positions, heights, verdict.fittedLoss);
}

TEST(FitVerdict, AFitThatEndedAtItsBakeIsNotScored) {
    const auto dir = scratchDir("fit_verdict_unmoved");
    const fit::FitOptions o = smallFit(dir);
    fit::FitScene scene(fit::resolved(o), programs(), cageOff(0.0f), reference());
    fit::FitRun run(fit::resolved(o), programs(), scene);
    run.startFrom(simplify::bakeFor(scene.cage, scene.reference, *run.fitter().maps()));
    const fit::FitState before = run.fitter().state();

    const simplify::FitVerdict verdict = simplify::keepTheFitWhereItPays(run, programs());
    EXPECT_FALSE(verdict.fitShips);
    EXPECT_FALSE(verdict.fitMoved);
    const fit::FitState after = run.fitter().state();
    ASSERT_EQ(after.groups.size(), 2u);  // the vertices and the heights
    for (size_t k = 0; k < after.groups.size(); ++k) EXPECT_EQ(after.groups[k].theta, before.groups[k].theta);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
