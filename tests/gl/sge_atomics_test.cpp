// G's sums: the gradient is accumulated in fixed point with integer atomics
// (glsl/fixed_point.glsl), so it repeats bit for bit whatever order the GPU's threads add in;
// the reported loss still uses float atomics, native (GL_NV_shader_atomic_float) or through a
// compare-and-swap loop where the extension is missing, and the two must agree.
#include <gtest/gtest.h>

#include "context/gl_context.h"
#include "gl_test_context.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"

namespace subdfit::test {
namespace {

struct Sums {
    std::vector<float> gradient;
    float loss;
};

Sums sumsWith(gl::ProgramCache& cache, const FitScene& scene, int samples) {
    fit::CageFitSettings settings;
    settings.resolution = scene.targets->resolution();
    fit::CageFitter fitter(cache, scene.cage, settings);
    const int views[] = {0, 1};
    for (int k = 0; k < samples; ++k) fitter.accumulate(*scene.targets, views);
    return {fitter.takeGradient(), fitter.takeMeanLoss()};
}

// A 6-quad cage seen large: every pixel of a face adds into the same few parameters, so the
// order of the adds differs from run to run.
FitScene contendedScene() {
    return makeFitScene(programs(), mesh::makeQuadSphere(1), mesh::makeLumpySphere(3, 0.2f, 2), 2, 96);
}

TEST(SgeAtomics, TheGradientRepeatsBitForBitUnderContention) {
    auto scene = contendedScene();
    const auto first = sumsWith(programs(), scene, 8);
    double scale = 0.0;
    for (float g : first.gradient) scale = std::max(scale, double(std::abs(g)));
    ASSERT_GT(scale, 0.0);
    for (int run = 0; run < 3; ++run)
        EXPECT_EQ(sumsWith(programs(), scene, 8).gradient, first.gradient) << "run " << run;
    expectNoGlError();
}

TEST(SgeAtomics, CompareAndSwapLossMatchesNativeFloatAtomics) {
    if (!context::currentGlInfo().hasAtomicFloat) GTEST_SKIP() << "no GL_NV_shader_atomic_float to compare with";
    auto scene = contendedScene();
    gl::ProgramCache native(gl::Defines{{"SUBDFIT_ATOMIC_FLOAT", ""}});
    gl::ProgramCache compareAndSwap;
    const auto a = sumsWith(native, scene, 8), b = sumsWith(compareAndSwap, scene, 8);
    EXPECT_EQ(a.gradient, b.gradient);  // no float atomics there at all
    ASSERT_GT(a.loss, 0.0f);
    // Same sums in a different order: float rounding only.
    EXPECT_NEAR(a.loss, b.loss, 1e-4 * a.loss);
    bool sawCas = false;
    for (const auto& v : compareAndSwap.variants())
        sawCas = sawCas || (v.name == "gradient" && !v.defines.count("SUBDFIT_ATOMIC_FLOAT"));
    EXPECT_TRUE(sawCas);
    expectNoGlError();
}

double roughness(const mesh::PolygonMesh& topology, const std::vector<glm::vec3>& positions) {
    const auto adjacency = mesh::vertexAdjacency(topology);
    double sum = 0.0;
    for (int v = 0; v < topology.vertexCount(); ++v) {
        glm::vec3 mean(0.0f);
        const int begin = adjacency.offsets[v], end = adjacency.offsets[v + 1];
        for (int k = begin; k < end; ++k) mean += positions[adjacency.neighbors[k]];
        if (end > begin) sum += glm::length(positions[v] - mean / float(end - begin));
    }
    return sum / topology.vertexCount();
}

TEST(SgePreconditioner, KeepsANoisyFitSmooth) {
    // A quad-sphere cage fitted to a plain sphere (the right answer is a uniform scaling, no
    // roughness at all) from few views at a low resolution, so the gradient is noisy. Without
    // preconditioning the cage picks up that noise as roughness; with (I + λL)⁻¹ far less.
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(6), mesh::makeLumpySphere(4, 0.0f, 4), 3, 64);
    double rough[2];
    for (int i = 0; i < 2; ++i) {
        fit::CageFitSettings settings;
        settings.resolution = 64;
        settings.smoothingLambda = i == 0 ? 0.0f : 4.0f;
        fit::CageFitter fitter(programs(), scene.cage, settings);
        for (int step = 0; step < 150; ++step) {
            const int view[] = {step % 3};
            fitter.step(*scene.targets, view, false);
        }
        rough[i] = roughness(scene.cage, fitter.vertices());
    }
    const double start = roughness(scene.cage, scene.cage.positions);
    std::printf("cage roughness: start %.4f, no preconditioner %.4f, lambda 4 %.4f\n", start, rough[0], rough[1]);
    EXPECT_LT(rough[1] - start, 0.5 * (rough[0] - start));
}

}  // namespace
}  // namespace subdfit::test
