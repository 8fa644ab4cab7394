#include "fit/finite_differences.h"

#include <glm/geometric.hpp>

namespace subdfit::fit {

double totalImageLoss(CageFitter& fitter, const scene::TargetSet& targets) {
    render::RenderTarget image(targets.resolution(), targets.resolution());
    double sum = 0.0;
    for (int v = 0; v < targets.size(); ++v) {
        fitter.render(targets.camera(v), image);
        const auto colour = image.readColor();
        const auto target = targets.readColor(v);
        for (size_t p = 0; p < colour.size(); ++p) {
            const glm::vec3 d = glm::vec3(colour[p]) - glm::vec3(target[p]);
            sum += double(glm::dot(d, d));
        }
    }
    return sum;
}

std::vector<double> vertexFiniteDifferences(CageFitter& fitter, const scene::TargetSet& targets,
                                            const std::vector<glm::vec3>& base, float h) {
    std::vector<double> gradient(base.size() * 3);
    auto moved = base;
    for (size_t i = 0; i < gradient.size(); ++i) {
        float& coordinate = moved[i / 3][int(i % 3)];
        const float original = coordinate;
        coordinate = original + h;
        fitter.setVertices(moved);
        const double plus = totalImageLoss(fitter, targets);
        coordinate = original - h;
        fitter.setVertices(moved);
        const double minus = totalImageLoss(fitter, targets);
        coordinate = original;
        gradient[i] = (plus - minus) / (2.0 * double(h));
    }
    fitter.setVertices(base);
    return gradient;
}

}  // namespace subdfit::fit
