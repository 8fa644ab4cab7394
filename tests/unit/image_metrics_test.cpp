// SSIM as Wang et al. define it, over the pixels either image covers: 1 for the same image,
// symmetric, lower for more noise, blind to how much empty background there is, and equal to a
// direct (non-separable) evaluation of the windowed formula.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fit/image_metrics.h"
#include "util/error.h"

namespace subdfit::fit {
namespace {

constexpr int kSize = 32;

// A shaded disc of radius 10 in the middle, alpha 1 on it and 0 around.
std::vector<glm::vec4> disc(int size = kSize) {
    std::vector<glm::vec4> image(size_t(size * size), glm::vec4(0.0f));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float dx = float(x) - size / 2.0f, dy = float(y) - size / 2.0f;
            if (dx * dx + dy * dy > 100.0f) continue;
            image[size_t(y * size + x)] = {0.5f + 0.04f * dx, 0.3f + 0.02f * dy, 0.6f + 0.01f * (dx - dy), 1.0f};
        }
    return image;
}

std::vector<glm::vec4> noisy(std::vector<glm::vec4> image, float amplitude, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> noise(-amplitude, amplitude);
    for (glm::vec4& p : image)
        if (p.a > 0.0f)
            for (int c = 0; c < 3; ++c) p[c] += noise(random);
    return image;
}

// The definition, window by window.
double directSsim(const std::vector<glm::vec4>& a, const std::vector<glm::vec4>& b, int size) {
    double taps[11], total = 0.0;
    for (int k = -5; k <= 5; ++k) {
        taps[k + 5] = std::exp(-k * k / 4.5);  // 2σ² = 4.5
        total += taps[k + 5];
    }
    double sum = 0.0;
    int covered = 0;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            if (a[size_t(y * size + x)].a <= 0.0f && b[size_t(y * size + x)].a <= 0.0f) continue;
            ++covered;
            for (int c = 0; c < 3; ++c) {
                double mx = 0, my = 0, xx = 0, yy = 0, xy = 0;
                for (int j = -5; j <= 5; ++j)
                    for (int i = -5; i <= 5; ++i) {
                        const size_t p = size_t(std::clamp(y + j, 0, size - 1) * size + std::clamp(x + i, 0, size - 1));
                        const double w = taps[i + 5] * taps[j + 5] / (total * total);
                        const double u = std::clamp(double(a[p][c]), 0.0, 1.0),
                                     v = std::clamp(double(b[p][c]), 0.0, 1.0);
                        mx += w * u;
                        my += w * v;
                        xx += w * u * u;
                        yy += w * v * v;
                        xy += w * u * v;
                    }
                const double c1 = 1e-4, c2 = 9e-4;
                sum += (2 * mx * my + c1) * (2 * (xy - mx * my) + c2) /
                       ((mx * mx + my * my + c1) * (xx - mx * mx + yy - my * my + c2));
            }
        }
    return sum / (3.0 * covered);
}

TEST(StructuralSimilarity, IsOneForTheSameImageAndForTwoEmptyOnes) {
    EXPECT_NEAR(structuralSimilarity(disc(), disc(), kSize, kSize), 1.0, 1e-9);
    const std::vector<glm::vec4> empty(kSize * kSize, glm::vec4(0.0f));
    EXPECT_EQ(structuralSimilarity(empty, empty, kSize, kSize), 1.0);
}

TEST(StructuralSimilarity, FallsWithNoiseAndIsSymmetric) {
    const auto clean = disc();
    const double light = structuralSimilarity(noisy(clean, 0.02f, 1), clean, kSize, kSize);
    const double heavy = structuralSimilarity(noisy(clean, 0.2f, 1), clean, kSize, kSize);
    EXPECT_LT(light, 1.0);
    EXPECT_LT(heavy, light);
    EXPECT_GT(heavy, -1.0);
    EXPECT_NEAR(structuralSimilarity(clean, noisy(clean, 0.2f, 1), kSize, kSize), heavy, 1e-12);
}

TEST(StructuralSimilarity, StaysFiniteOnNonFinitePixelsAndRefusesAMismatchedSize) {
    auto broken = disc();
    broken[size_t(16 * kSize + 16)] = glm::vec4(std::nanf(""), INFINITY, -INFINITY, 1.0f);
    const double score = structuralSimilarity(broken, disc(), kSize, kSize);
    EXPECT_TRUE(std::isfinite(score));
    EXPECT_LT(score, 1.0);
    EXPECT_THROW(structuralSimilarity(disc(), disc(kSize - 1), kSize, kSize), Error);
}

TEST(StructuralSimilarity, MatchesTheWindowedDefinition) {
    const auto clean = disc(), other = noisy(clean, 0.1f, 7);
    EXPECT_NEAR(structuralSimilarity(other, clean, kSize, kSize), directSsim(other, clean, kSize), 1e-9);
}

TEST(StructuralSimilarity, EmptyBackgroundDoesNotLiftTheScore) {
    // The same disc and noise framed in twice the empty border: the covered pixels score alike.
    const auto clean = disc(), other = noisy(clean, 0.1f, 3);
    auto framed = [](const std::vector<glm::vec4>& image) {
        std::vector<glm::vec4> out(size_t(4 * kSize * kSize), glm::vec4(0.0f));
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                out[size_t((y + kSize / 2) * 2 * kSize + x + kSize / 2)] = image[size_t(y * kSize + x)];
        return out;
    };
    EXPECT_NEAR(structuralSimilarity(framed(other), framed(clean), 2 * kSize, 2 * kSize),
                structuralSimilarity(other, clean, kSize, kSize), 1e-9);
}

}  // namespace
}  // namespace subdfit::fit
