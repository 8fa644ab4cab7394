#include "orbit_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace subdfit::view {
namespace {

constexpr float kFovDegrees = 35.0f;  // as render::orbitCamera, so the start framing matches the fit's views
constexpr float kRadiansPerPixel = 0.008f;

}  // namespace

void OrbitCamera::reset() {
    yaw_ = glm::radians(-150.0f);
    pitch_ = glm::radians(20.0f);
    distance_ = 1.15f / std::sin(glm::radians(kFovDegrees) * 0.5f);  // unit sphere plus 15 %
    target_ = glm::vec3(0.0f);
}

void OrbitCamera::orbit(glm::vec2 pixels) {
    yaw_ -= pixels.x * kRadiansPerPixel;
    // Short of the poles, where the up vector would flip.
    pitch_ = std::clamp(pitch_ + pixels.y * kRadiansPerPixel, -1.55f, 1.55f);
}

void OrbitCamera::pan(glm::vec2 pixels, float viewHeight) {
    const render::Camera c = camera(1.0f);
    const glm::vec3 right(c.view[0][0], c.view[1][0], c.view[2][0]);
    const glm::vec3 up(c.view[0][1], c.view[1][1], c.view[2][1]);
    // One pixel moves the target by one pixel's footprint at the target's depth.
    const float perPixel = 2.0f * distance_ * std::tan(glm::radians(kFovDegrees) * 0.5f) / std::max(1.0f, viewHeight);
    target_ += (-pixels.x * right + pixels.y * up) * perPixel;
}

void OrbitCamera::zoom(float wheelClicks) {
    distance_ = std::clamp(distance_ * std::pow(0.88f, wheelClicks), 0.05f, 50.0f);
}

render::Camera OrbitCamera::camera(float aspect) const {
    const glm::vec3 direction(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_), std::cos(pitch_) * std::cos(yaw_));
    render::Camera c;
    c.eye = target_ + direction * distance_;
    c.view = glm::lookAt(c.eye, target_, glm::vec3(0, 1, 0));
    // The scene fits the unit sphere: keep it between the planes wherever the target has been panned.
    const float reach = 1.5f + glm::length(target_);
    c.projection =
        glm::perspective(glm::radians(kFovDegrees), aspect, std::max(0.01f, distance_ - reach), distance_ + reach);
    return c;
}

}  // namespace subdfit::view
