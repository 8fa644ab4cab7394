#include "simplify/compare/comparison_image.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cmath>

#include "io/image_io.h"

namespace subdfit::simplify {
namespace {

constexpr float kHeatScale = 0.25f;  // RMS error shown as white

glm::vec4 heat(const glm::vec4& a, const glm::vec4& b) {
    const glm::vec3 d = glm::vec3(a) - glm::vec3(b);
    const float t = glm::clamp(std::sqrt(glm::dot(d, d) / 3.0f) / kHeatScale, 0.0f, 1.0f);
    // Black → red → yellow → white, in thirds.
    return {glm::clamp(3.0f * t, 0.0f, 1.0f), glm::clamp(3.0f * t - 1.0f, 0.0f, 1.0f),
            glm::clamp(3.0f * t - 2.0f, 0.0f, 1.0f), 1.0f};
}

}  // namespace

void writeComparison(const std::filesystem::path& path, int res, const std::vector<glm::vec4>& reference,
                     const std::vector<const std::vector<glm::vec4>*>& candidates) {
    const int columns = 1 + int(candidates.size());
    const int width = columns * res, height = 2 * res;
    // Bottom-up like the inputs: the renders' row is the upper half (rows res..2res−1).
    std::vector<glm::vec4> out(size_t(width) * size_t(height), glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
    auto put = [&](int column, bool upper, int x, int y, const glm::vec4& c) {
        out[size_t(y + (upper ? res : 0)) * size_t(width) + size_t(column * res + x)] = c;
    };
    for (int y = 0; y < res; ++y)
        for (int x = 0; x < res; ++x) {
            const size_t i = size_t(y) * size_t(res) + size_t(x);
            put(0, true, x, y, reference[i]);
            for (size_t c = 0; c < candidates.size(); ++c) {
                put(int(c) + 1, true, x, y, (*candidates[c])[i]);
                put(int(c) + 1, false, x, y, heat((*candidates[c])[i], reference[i]));
            }
        }
    io::writeImage(path, out, width, height);
}

}  // namespace subdfit::simplify
