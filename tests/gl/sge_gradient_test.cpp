// The per-pixel SGE gradient against central finite differences of the same rasteriser.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "gl_test_context.h"
#include "gradient_checks.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"

namespace subdfit::test {
namespace {

TEST(SgeGradient, AgreesWithCentralFiniteDifferences) {
    // A 54-quad sphere cage against a lumpy sphere: 168 vertex parameters, two views.
    const float epsilon = 0.01f;
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(3), mesh::makeLumpySphere(4, 0.2f, 3), 2, 96);
    fit::CageFitSettings settings;
    settings.resolution = 96;
    settings.vertices.epsilon = epsilon;
    fit::CageFitter fitter(programs(), scene.cage, settings);
    const int views[] = {0, 1};

    // SGE: mean of K samples of Σ_p Δ_p / (2 s_i ε) (each sample draws fresh signs).
    const int samples = 256;
    for (int k = 0; k < samples; ++k) fitter.accumulate(*scene.targets, views);
    const auto raw = fitter.takeGradient();
    std::vector<double> sge(raw.begin(), raw.end());
    for (auto& g : sge) g /= samples;

    // Central differences with the same step: (f(θ + ε e_i) − f(θ − ε e_i)) / 2ε.
    const auto reference = fit::vertexFiniteDifferences(fitter, *scene.targets, scene.cage.positions, epsilon);

    for (double g : sge) ASSERT_TRUE(std::isfinite(g));
    // The estimator is unbiased to first order; its variance per sample is the sum of the
    // squared derivatives of the ~50 other parameters sharing each pixel. With K = 256 samples
    // the expected cosine is about 1/sqrt(1 + 50/256) ≈ 0.9 (measured: see the note); 0.8
    // leaves room for seeds, while an estimator with wrong signs, scale or pixel sets
    // (full-image or the wrong faces) lands far below it.
    const double similarity = cosine(sge, reference);
    RecordProperty("cosine_similarity", std::to_string(similarity));
    std::printf("SGE vs finite differences: cosine %.3f over %zu parameters, %d samples\n", similarity, sge.size(),
                samples);
    EXPECT_GT(similarity, 0.8);
    // Same magnitude, not just the same direction.
    const double normRatio = std::sqrt(std::inner_product(sge.begin(), sge.end(), sge.begin(), 0.0) /
                                       std::inner_product(reference.begin(), reference.end(), reference.begin(), 0.0));
    EXPECT_GT(normRatio, 0.7);
    EXPECT_LT(normRatio, 1.5);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
