#include "fit/image_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "util/error.h"

namespace subdfit::fit {

double meanPixelLoss(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& target) {
    double sum = 0.0;
    for (size_t i = 0; i < image.size(); ++i) {
        const glm::vec3 d = glm::vec3(image[i]) - glm::vec3(target[i]);
        sum += double(glm::dot(d, d));
    }
    return image.empty() ? 0.0 : sum / double(image.size());
}

double psnrFromLoss(double meanPixelLoss) {
    const double mse = std::max(meanPixelLoss / 3.0, 1e-12);  // capped at 120 dB for identical images
    return 10.0 * std::log10(1.0 / mse);
}

namespace {

constexpr int kRadius = 5;  // 11 taps
constexpr double kSigma = 1.5;

std::array<double, 2 * kRadius + 1> gaussianTaps() {
    std::array<double, 2 * kRadius + 1> taps{};
    double sum = 0.0;
    for (int k = -kRadius; k <= kRadius; ++k) {
        taps[size_t(k + kRadius)] = std::exp(-k * k / (2.0 * kSigma * kSigma));
        sum += taps[size_t(k + kRadius)];
    }
    for (double& t : taps) t /= sum;
    return taps;
}

// One pass of the Gaussian along `lines` lines of `length` values (`step` apart within a line,
// `lineStep` between lines), edges clamped.
void blurLines(const std::vector<double>& in, std::vector<double>& out, int lines, int length, size_t step,
               size_t lineStep) {
    static const auto taps = gaussianTaps();
    for (int line = 0; line < lines; ++line)
        for (int i = 0; i < length; ++i) {
            double sum = 0.0;
            for (int k = -kRadius; k <= kRadius; ++k)
                sum += taps[size_t(k + kRadius)] *
                       in[size_t(line) * lineStep + size_t(std::clamp(i + k, 0, length - 1)) * step];
            out[size_t(line) * lineStep + size_t(i) * step] = sum;
        }
}

// The Gaussian-weighted local mean of `values` around every pixel (separable: rows, then columns).
std::vector<double> blurred(const std::vector<double>& values, int width, int height) {
    std::vector<double> rows(values.size()), out(values.size());
    blurLines(values, rows, height, width, 1, size_t(width));
    blurLines(rows, out, width, height, size_t(width), 1);
    return out;
}

// A channel value as SSIM's constants assume it: in [0, 1], and 0 for a non-finite one.
double unitValue(float v) { return std::isfinite(v) ? std::clamp(double(v), 0.0, 1.0) : 0.0; }

}  // namespace

double structuralSimilarity(const std::vector<glm::vec4>& image, const std::vector<glm::vec4>& target, int width,
                            int height) {
    const size_t pixels = size_t(std::max(width, 0)) * size_t(std::max(height, 0));
    if (image.size() != pixels || target.size() != pixels)
        throw Error("SSIM of images of " + std::to_string(image.size()) + " and " + std::to_string(target.size()) +
                    " pixels as " + std::to_string(width) + "x" + std::to_string(height));
    std::vector<char> covered(pixels);
    size_t coveredCount = 0;
    for (size_t i = 0; i < pixels; ++i) {
        covered[i] = image[i].a > 0.0f || target[i].a > 0.0f;
        coveredCount += size_t(covered[i]);
    }
    if (coveredCount == 0) return 1.0;
    constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;
    double sum = 0.0;
    std::vector<double> x(pixels), y(pixels), xx(pixels), yy(pixels), xy(pixels);
    for (int c = 0; c < 3; ++c) {
        for (size_t i = 0; i < pixels; ++i) {
            x[i] = unitValue(image[i][c]);
            y[i] = unitValue(target[i][c]);
            xx[i] = x[i] * x[i];
            yy[i] = y[i] * y[i];
            xy[i] = x[i] * y[i];
        }
        const auto mx = blurred(x, width, height), my = blurred(y, width, height);
        const auto sxx = blurred(xx, width, height), syy = blurred(yy, width, height), sxy = blurred(xy, width, height);
        for (size_t i = 0; i < pixels; ++i) {
            if (!covered[i]) continue;
            const double varX = sxx[i] - mx[i] * mx[i], varY = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
            sum += (2.0 * mx[i] * my[i] + kC1) * (2.0 * cov + kC2) /
                   ((mx[i] * mx[i] + my[i] * my[i] + kC1) * (varX + varY + kC2));
        }
    }
    return sum / (3.0 * double(coveredCount));
}

}  // namespace subdfit::fit
