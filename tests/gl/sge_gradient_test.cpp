// The per-pixel SGE gradient against central finite differences of the same rasteriser, and one
// sample of it against the rule G implements, recomputed on the CPU.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "gl_test_context.h"
#include "gradient_checks.h"
#include "mesh/procedural.h"
#include "optim/sign_hash.h"
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

// G sums most pixels per face or per pair of faces before handing them to the vertices; the
// result must be what the rule gives pixel by pixel: Δ_p / 2ε, with sign s_i, to each parameter
// of the union of the base vertices reaching the face each render saw at p.
TEST(SgeGradient, OneSampleFollowsTheUnionRule) {
    constexpr int kResolution = 128;
    const float epsilon = 0.02f;  // moves face edges by a pixel or more: many pixels change face
    auto scene = makeFitScene(programs(), mesh::makeQuadSphere(3), mesh::makeLumpySphere(4, 0.2f, 3), 1, kResolution);
    fit::CageFitSettings settings;
    settings.resolution = kResolution;
    settings.vertices.epsilon = epsilon;
    fit::CageFitter fitter(programs(), scene.cage, settings);
    const int views[] = {0};
    fitter.accumulate(*scene.targets, views, false);  // the first sample: counter 0
    const auto gpu = fitter.takeGradient();

    // θ± of that sample, drawn as plain renders.
    const std::uint32_t seed = settings.seed ^ fitter.vertexGroup().seedSalt();
    auto sign = [&](size_t i) { return optim::perturbationSign(std::uint32_t(i), 0u, seed); };
    render::RenderTarget image(kResolution, kResolution);
    auto renderAt = [&](float direction) {
        auto points = scene.cage.positions;
        for (size_t v = 0; v < points.size(); ++v)
            for (int c = 0; c < 3; ++c) points[v][c] += direction * sign(3 * v + size_t(c)) * epsilon;
        fitter.setVertices(points);
        fitter.render(scene.targets->camera(0), image);
        return std::pair{image.readColor(), image.readFaceId()};
    };
    const auto [colorPlus, facePlus] = renderAt(1.0f);
    const auto [colorMinus, faceMinus] = renderAt(-1.0f);
    const auto target = scene.targets->readColor(0);

    const auto& offsets = fitter.patches().faceVertexOffsets;
    const auto& vertices = fitter.patches().faceVertexIndices;
    std::vector<double> expected(gpu.size(), 0.0);
    int facesDiffer = 0;
    for (size_t p = 0; p < target.size(); ++p) {
        const int fp = facePlus[p], fm = faceMinus[p];
        if (fp < 0 && fm < 0) continue;
        auto error = [&](const glm::vec4& color) {
            const glm::vec3 e = glm::vec3(color) - glm::vec3(target[p]);
            return glm::dot(e, e);
        };
        const double delta = double(error(colorPlus[p]) - error(colorMinus[p]));
        if (delta == 0.0) continue;
        std::vector<int> reached;
        for (int f : {fp, fm})
            if (f >= 0) reached.insert(reached.end(), vertices.begin() + offsets[f], vertices.begin() + offsets[f + 1]);
        std::sort(reached.begin(), reached.end());
        reached.erase(std::unique(reached.begin(), reached.end()), reached.end());
        facesDiffer += fp != fm && fp >= 0 && fm >= 0;
        for (int v : reached)
            for (size_t c = 0; c < 3; ++c)
                expected[3 * size_t(v) + c] += delta / (2.0 * epsilon) * sign(3 * size_t(v) + c);
    }
    RecordProperty("pixels_between_two_faces", std::to_string(facesDiffer));
    EXPECT_GT(facesDiffer, 100);  // the pair sums are exercised

    double scale = 0.0, worst = 0.0;
    for (size_t i = 0; i < gpu.size(); ++i) {
        scale = std::max(scale, std::abs(expected[i]));
        worst = std::max(worst, std::abs(double(gpu[i]) - expected[i]));
    }
    ASSERT_GT(scale, 0.0);
    std::printf("G against the union rule: largest difference %.2e of the largest term %.2e\n", worst, scale);
    EXPECT_LT(worst, 1e-4 * scale);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
