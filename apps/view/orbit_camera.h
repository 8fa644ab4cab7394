#pragma once
// The viewer's camera: orbits a target point (initially the origin of the normalised scene),
// framing the unit sphere like render::orbitCamera at the start. Mouse input comes in as
// deltas in pixels, so the class knows nothing of the window system.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "render/camera.h"

namespace subdfit::view {

class OrbitCamera {
public:
    OrbitCamera() { reset(); }

    void reset();
    void orbit(glm::vec2 pixels);                  // left drag
    void pan(glm::vec2 pixels, float viewHeight);  // right or middle drag
    void zoom(float wheelClicks);                  // mouse wheel

    render::Camera camera(float aspect) const;

private:
    float yaw_ = 0.0f, pitch_ = 0.0f;  // radians
    float distance_ = 1.0f;
    glm::vec3 target_{0.0f};
};

}  // namespace subdfit::view
