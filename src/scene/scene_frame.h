#pragma once
// Every scene is fitted in a normalised frame: the reference's bounding box centred at the
// origin and scaled into the unit sphere. Cameras, ε and learning rates are then meaningful
// whatever the asset's units (a 1e-4 or a 1e4 scene behaves the same); results go back out
// through the inverse.
#include <glm/vec3.hpp>
#include <vector>

namespace subdfit::scene {

struct SceneFrame {
    glm::vec3 center{0.0f};
    float scale = 1.0f;  // world -> normalised

    glm::vec3 toNormalized(const glm::vec3& p) const { return (p - center) * scale; }
    glm::vec3 toWorld(const glm::vec3& p) const { return p / scale + center; }

    std::vector<glm::vec3> toNormalized(const std::vector<glm::vec3>& points) const;
    std::vector<glm::vec3> toWorld(const std::vector<glm::vec3>& points) const;
};

// Throws subdfit::Error when the points are empty, non-finite or all coincident.
SceneFrame frameAround(const std::vector<glm::vec3>& points);

}  // namespace subdfit::scene
