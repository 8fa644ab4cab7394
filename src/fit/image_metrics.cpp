#include "fit/image_metrics.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

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

}  // namespace subdfit::fit
