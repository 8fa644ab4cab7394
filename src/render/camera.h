#pragma once
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <cstdint>
#include <vector>

namespace subdfit::render {

struct Camera {
    glm::mat4 view{1.0f};
    glm::mat4 projection{1.0f};
    glm::vec3 eye{0.0f};
    glm::mat4 viewProjection() const { return projection * view; }
};

// A perspective camera on the sphere of directions, looking at the origin, framing the unit
// sphere (subdfit normalises every scene into it) with a small margin.
Camera orbitCamera(const glm::vec3& direction, float fovDegrees = 35.0f);

// `count` directions spread evenly (Fibonacci lattice) and turned by a rotation drawn from
// `seed`, so different seeds give different but equally even view sets.
std::vector<Camera> orbitCameras(int count, std::uint32_t seed, float fovDegrees = 35.0f);

}  // namespace subdfit::render
