#include "render/camera.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <cmath>
#include <random>

namespace subdfit::render {

Camera orbitCamera(const glm::vec3& direction, float fovDegrees) {
    const float halfFov = glm::radians(fovDegrees) * 0.5f;
    const float distance = 1.15f / std::sin(halfFov);  // unit sphere plus 15 % margin
    Camera camera;
    camera.eye = glm::normalize(direction) * distance;
    // Up is +Y unless the view looks straight along it.
    glm::vec3 up = std::abs(glm::normalize(direction).y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    camera.view = glm::lookAt(camera.eye, glm::vec3(0.0f), up);
    camera.projection = glm::perspective(2.0f * halfFov, 1.0f, distance - 1.5f, distance + 1.5f);
    return camera;
}

std::vector<Camera> orbitCameras(int count, std::uint32_t seed, float fovDegrees) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal;
    const glm::quat rotation = glm::normalize(glm::quat(normal(rng), normal(rng), normal(rng), normal(rng)));
    const float golden = float(M_PI) * (3.0f - std::sqrt(5.0f));
    std::vector<Camera> cameras;
    for (int i = 0; i < count; ++i) {
        const float y = 1.0f - 2.0f * (float(i) + 0.5f) / float(count);
        const float r = std::sqrt(std::max(0.0f, 1.0f - y * y));
        const glm::vec3 d(r * std::cos(golden * float(i)), y, r * std::sin(golden * float(i)));
        cameras.push_back(orbitCamera(rotation * d, fovDegrees));
    }
    return cameras;
}

}  // namespace subdfit::render
