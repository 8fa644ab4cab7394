#include "surface/appearance_atlas.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <numeric>

#include "util/error.h"

namespace subdfit::surface {

TexelLayout atlasLattice(int size) {
    SUBDFIT_CHECK(size >= 2 && size <= kMaxAtlasSize);
    TexelLayout layout;
    layout.resolution = size - 1;
    layout.ptexFaceCount = 1;
    layout.nodeCount = size * size;
    layout.faceNodes.resize(size_t(layout.nodeCount));
    std::iota(layout.faceNodes.begin(), layout.faceNodes.end(), 0);
    layout.halo.assign(4 * size_t(size), -1);
    return layout;
}

int cornerPoint(const TexelLayout& corners, int face, int corner) {
    static constexpr int kI[4] = {0, 1, 1, 0}, kJ[4] = {0, 0, 1, 1};
    return corners.node(face, kI[corner], kJ[corner]);
}

glm::vec2 atlasUvAt(const AppearanceAtlas& atlas, int face, float u, float v) {
    u = glm::clamp(u, 0.0f, 1.0f), v = glm::clamp(v, 0.0f, 1.0f);
    const glm::vec2* c = &atlas.cornerUvs[4 * size_t(face)];
    return glm::mix(glm::mix(c[0], c[1], u), glm::mix(c[3], c[2], u), v);
}

glm::mat2 atlasUvJacobian(const AppearanceAtlas& atlas, int face, float u, float v) {
    u = glm::clamp(u, 0.0f, 1.0f), v = glm::clamp(v, 0.0f, 1.0f);
    const glm::vec2* c = &atlas.cornerUvs[4 * size_t(face)];
    return glm::mat2(glm::mix(c[1] - c[0], c[2] - c[3], v), glm::mix(c[3] - c[0], c[2] - c[1], u));
}

glm::vec4 atlasTangent(glm::vec3 normal, glm::vec3 dPdu, glm::vec3 dPdv, const glm::mat2& jacobian,
                       glm::vec4 fallback) {
    // [∂P/∂s ∂P/∂t] = [∂P/∂u ∂P/∂v] · J⁻¹, J's columns ∂(s, t)/∂u and ∂(s, t)/∂v.
    const float det = glm::determinant(jacobian);
    if (!(std::abs(det) > 1e-12f)) return fallback;
    const glm::vec3 alongS = (dPdu * jacobian[1].y - dPdv * jacobian[0].y) / det;
    const glm::vec3 alongT = (dPdv * jacobian[0].x - dPdu * jacobian[1].x) / det;
    const glm::vec3 inPlane = alongS - glm::dot(alongS, normal) * normal;
    const float length = glm::length(inPlane);
    if (!(length > 0.0f) || !std::isfinite(length)) return fallback;
    const glm::vec3 tangent = inPlane / length;
    return glm::vec4(tangent, glm::dot(glm::cross(normal, tangent), alongT) > 0.0f ? -1.0f : 1.0f);
}

glm::vec2 latticeUv(int size, glm::vec2 atlasUv) {
    return glm::clamp((atlasUv * float(size) - 0.5f) / float(size - 1), 0.0f, 1.0f);
}

}  // namespace subdfit::surface
