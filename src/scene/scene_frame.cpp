#include "scene/scene_frame.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace subdfit::scene {

std::vector<glm::vec3> SceneFrame::toNormalized(const std::vector<glm::vec3>& points) const {
    std::vector<glm::vec3> out;
    out.reserve(points.size());
    for (const auto& p : points) out.push_back(toNormalized(p));
    return out;
}

std::vector<glm::vec3> SceneFrame::toWorld(const std::vector<glm::vec3>& points) const {
    std::vector<glm::vec3> out;
    out.reserve(points.size());
    for (const auto& p : points) out.push_back(toWorld(p));
    return out;
}

SceneFrame frameAround(const std::vector<glm::vec3>& points) {
    if (points.empty()) throw Error("no vertices");
    // Bounds in double: a 1e4-sized scene with 1e-4 detail must not lose its centre to rounding.
    glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const auto& p : points) {
        lo = glm::min(lo, glm::dvec3(p));
        hi = glm::max(hi, glm::dvec3(p));
    }
    const double radius = 0.5 * glm::length(hi - lo);
    if (!std::isfinite(radius)) throw Error("the bounds of its vertices are not finite");
    if (radius <= 0.0) throw Error("every vertex is at the same point: there is nothing to see");
    SceneFrame frame;
    frame.center = glm::vec3(0.5 * (lo + hi));
    frame.scale = float(1.0 / radius);
    return frame;
}

}  // namespace subdfit::scene
