// The two float-accumulation paths of G (GL_NV_shader_atomic_float, and the CAS loop used where
// the extension is missing) give the same gradient, including under heavy contention.
#include <gtest/gtest.h>

#include "context/gl_context.h"
#include "gl_test_context.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"

namespace subdfit::test {
namespace {

std::vector<float> gradientWith(gl::ProgramCache& cache, const FitScene& scene, int samples) {
    fit::CageFitSettings settings;
    settings.resolution = scene.targets->resolution();
    fit::CageFitter fitter(cache, scene.cage, settings);
    const int views[] = {0, 1};
    for (int k = 0; k < samples; ++k) fitter.accumulate(*scene.targets, views);
    return fitter.takeGradient();
}

TEST(SgeAtomics, CompareAndSwapPathMatchesNativeFloatAtomics) {
    if (!context::currentGlInfo().hasAtomicFloat) GTEST_SKIP() << "no GL_NV_shader_atomic_float to compare with";
    // A 6-quad cage seen large: every pixel of a face adds into the same few parameters.
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(1), mesh::makeLumpySphere(3, 0.2f, 2), 2, 96);
    gl::ProgramCache native(gl::Defines{{"SUBDFIT_ATOMIC_FLOAT", ""}});
    gl::ProgramCache compareAndSwap;
    const auto a = gradientWith(native, scene, 8);
    const auto b = gradientWith(compareAndSwap, scene, 8);
    ASSERT_EQ(a.size(), b.size());
    double scale = 0.0, worst = 0.0;
    for (size_t i = 0; i < a.size(); ++i) {
        ASSERT_TRUE(std::isfinite(a[i]) && std::isfinite(b[i]));
        scale = std::max(scale, double(std::abs(a[i])));
        worst = std::max(worst, double(std::abs(a[i] - b[i])));
    }
    ASSERT_GT(scale, 0.0);
    // Same sums in a different order: float rounding only (thousands of terms, ~1e-7 each).
    EXPECT_LT(worst / scale, 1e-4) << "largest difference " << worst << " of " << scale;
    // And the CAS variant really was a different program.
    bool sawCas = false;
    for (const auto& v : compareAndSwap.variants()) sawCas = sawCas || (v.name == "gradient" && !v.defines.count("SUBDFIT_ATOMIC_FLOAT"));
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
