// The fit with its default settings (scale-free steps, the plateau schedule, the best state kept)
// on the cases a technical artist brings: a noised creased cage, a dense cage, a dense cage that
// already starts close to the answer.
#include <gtest/gtest.h>

#include <cstdio>

#include "fit/fit_run.h"
#include "geometry/surface_distance.h"
#include "gl_test_context.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "simplify/cage/initial_cage.h"
#include "surface/tessellation.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

fit::FitOptions defaultsWith(int views, int resolution, int steps, const std::string& name) {
    fit::FitOptions o;
    o.views = views;
    o.holdoutViews = 4;
    o.resolution = resolution;
    o.steps = steps;
    o.out = scratchDir(name);
    return o;
}

// Distance of the cage's limit surface to `truth` (both in the scene's normalised frame), each
// tessellated with `segments` per face edge.
double surfaceError(fit::FitRun& run, const mesh::PolygonMesh& truth, int segments = 3) {
    mesh::PolygonMesh cage = run.scene().cage;
    cage.positions = run.fitter().vertices();
    return geometry::surfaceDistance(surface::limitMesh(cage, segments), truth, 20000).chamferL2Squared;
}

mesh::PolygonMesh normalised(mesh::PolygonMesh mesh, const fit::FitScene& scene) {
    mesh.positions = scene.frame.toNormalized(mesh.positions);
    return mesh;
}

class CreasedCageRecovery : public ::testing::TestWithParam<const char*> {};

// A noised creased cage fitted to renders of its own limit surface ends with a cleaner cage, not
// only a closer surface: the vertex error falls together with the surface distance.
TEST_P(CreasedCageRecovery, VertexErrorAndSurfaceDistanceFall) {
    const auto truthWorld = mesh::loadMesh(assetPath(std::string("osd-shapes/") + GetParam()));
    fit::FitOptions o = defaultsWith(8, 128, 300, std::string("recovery_") + GetParam());
    mesh::PolygonMesh noisedWorld = truthWorld;
    int segments = 0;  // the true limit surface's: finer than the fit draws it, a segment a pixel
    {
        fit::FitScene probe(fit::resolved(o), programs(), truthWorld, surface::limitMesh(truthWorld, 6));
        noisedWorld.positions = probe.frame.toWorld(noised(probe.cage.positions, 0.03f, 11));
        segments = std::max(6, fit::screenSegments(probe.cage, o.resolution, 1.0f));
    }
    const auto referenceWorld = surface::limitMesh(truthWorld, segments);
    fit::FitScene scene(fit::resolved(o), programs(), noisedWorld, referenceWorld);
    const auto truth = normalised(truthWorld, scene).positions;
    const auto truthSurface = normalised(referenceWorld, scene);
    fit::FitRun run(fit::resolved(o), programs(), scene);

    const double vertexBefore = rmsDistance(run.fitter().vertices(), truth);
    const double surfaceBefore = surfaceError(run, truthSurface, segments);
    run.run(o.out / "checkpoint.bin");
    const double vertexAfter = rmsDistance(run.fitter().vertices(), truth);
    const double surfaceAfter = surfaceError(run, truthSurface, segments);
    std::printf("%s: vertex RMS %.4f -> %.4f, surface Chamfer %.3e -> %.3e after %d steps (%s)\n", GetParam(),
                vertexBefore, vertexAfter, surfaceBefore, surfaceAfter, run.step(), fit::toString(run.stopReason()));
    EXPECT_LT(vertexAfter, vertexBefore);
    EXPECT_LT(surfaceAfter, 0.7 * surfaceBefore);
    expectNoGlError();
}

INSTANTIATE_TEST_SUITE_P(Shapes, CreasedCageRecovery,
                         ::testing::Values("catmark_cube_creases1.obj", "catmark_pyramid_creases0.obj",
                                           "catmark_chaikin0.obj", "catmark_single_crease.obj"),
                         [](const auto& info) {
                             std::string name = info.param;
                             return name.substr(0, name.find('.'));
                         });

// ε and the step are fractions of the cage's mean edge: a cage of ten times the faces takes
// steps in proportion and, with more freedom, fits the same target at least as well in the same
// number of steps (with absolute settings it overshot and fitted worse).
TEST(ScaleFreeSettings, DenseCageFitsAtLeastAsWellAsASparseOne) {
    const auto reference = mesh::makeLumpySphere(4, 0.15f, 3, 16);
    auto chamferAfter = [&](int n) {
        mesh::PolygonMesh cage = mesh::makeQuadSphere(n);
        for (auto& p : cage.positions) p *= 0.9f;
        fit::FitOptions o = defaultsWith(12, 128, 100, "dense_" + std::to_string(n));
        o.schedule = fit::Schedule::Anneal;  // exactly the same number of steps for both
        fit::FitScene scene(fit::resolved(o), programs(), cage, reference);
        fit::FitRun run(fit::resolved(o), programs(), scene);
        run.run(o.out / "checkpoint.bin");
        const double chamfer = surfaceError(run, scene.reference);
        std::printf("%d faces: Chamfer %.3e after %d steps\n", cage.faceCount(), chamfer, run.step());
        return chamfer;
    };
    const double sparse = chamferAfter(7);  // 294 faces
    const double dense = chamferAfter(22);  // 2 904 faces
    EXPECT_LE(dense, sparse);
    expectNoGlError();
}

// A dense limit-interpolated cage already lies on the reference; every step from there risks
// making it worse. The fit keeps its best monitored state, so it never ends above its start.
TEST(KeepBest, DenseLimitInterpolatedCageNeverEndsWorseThanItStarted) {
    const auto reference = mesh::loadMesh(assetPath("spot/spot_triangulated.obj"));
    const auto cage = simplify::initialCage(reference, {.faces = 5000});
    fit::FitOptions o = defaultsWith(6, 128, 20, "keep_best");
    o.tessLevel = 2;  // 15 000 ptex faces already: llvmpipe's time goes to triangles
    fit::FitScene scene(fit::resolved(o), programs(), cage, reference);
    fit::FitRun run(fit::resolved(o), programs(), scene);
    const double before = fit::score(run.fitter(), scene.holdout).loss;
    run.run(o.out / "checkpoint.bin");
    const double after = fit::score(run.fitter(), scene.holdout).loss;
    std::printf("%d-face cage: held-out loss %.4e -> %.4e after %d steps (%s)\n", cage.faceCount(), before, after,
                run.step(), fit::toString(run.stopReason()));
    EXPECT_LE(after, before);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
