#include "surface/displaced_surface.h"

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <optional>

#include "util/error.h"

namespace subdfit::surface {
namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The unit vector along v, unless v is non-finite, zero, or shorter than 1e-7 of `scale` (the
// size of what it was computed from, so below that it is rounding noise). v is divided by its
// largest component first: squaring a tiny vector's components would underflow and lose the
// direction (normals 3e-4 off unit length came out of a collapsed corner before this).
std::optional<glm::vec3> direction(const glm::vec3& v, float scale) {
    const float largest = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!finite(v) || !(largest > 0.0f)) return std::nullopt;
    const glm::vec3 w = v / largest;
    const float length = glm::length(w);  // in [1, sqrt(3)]
    if (largest * length <= 1e-7f * scale) return std::nullopt;
    return w / length;
}

// The size a cross product of a and b is measured against (it may underflow to 0 for tiny
// vectors, which only makes direction() more permissive).
float lengthProduct(const glm::vec3& a, const glm::vec3& b) { return glm::length(a) * glm::length(b); }

glm::vec3 anyPerpendicular(const glm::vec3& n) {
    const glm::vec3 axis = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::normalize(glm::cross(n, axis));
}

}  // namespace

DisplacedSurface::DisplacedSurface(const mesh::PolygonMesh& cage, const SurfaceMaps& maps)
    : maps_(maps), evaluator_(cage), patchPoints_(evaluator_.patchPoints(cage.positions)) {
    SUBDFIT_CHECK(!maps.hasDisplacement() || maps.layout.ptexFaceCount == evaluator_.ptexFaceCount());
    SUBDFIT_CHECK(!maps.hasDisplacement() || maps.displacement.size() == size_t(maps.layout.nodeCount));
}

// The limit point with a unit normal everywhere. Where cross(dPdu, dPdv) vanishes (the ptex
// parametrisation can collapse at a corner; a degenerate cage face collapses whole), the limit
// normal is still continuous, so a point nudged towards the face centre gives it.
DisplacedSurface::LimitPoint DisplacedSurface::limitPoint(int face, float u, float v) const {
    auto evaluate = [&](float pu, float pv) {
        const subdiv::LimitSample s = evaluator_.evaluate(face, pu, pv, patchPoints_);
        return LimitPoint{s.position, s.dPdu, s.dPdv, glm::vec3(0.0f)};
    };
    LimitPoint point = evaluate(u, v);
    if (const auto n = direction(glm::cross(point.dPdu, point.dPdv), lengthProduct(point.dPdu, point.dPdv))) {
        point.normal = *n;
        return point;
    }
    for (float step : {1e-4f, 1e-3f, 1e-2f, 1e-1f, 0.5f}) {
        const LimitPoint nudged = evaluate(u + (0.5f - u) * step, v + (0.5f - v) * step);
        if (const auto n = direction(glm::cross(nudged.dPdu, nudged.dPdv), lengthProduct(nudged.dPdu, nudged.dPdv))) {
            point.normal = *n;
            return point;
        }
    }
    point.normal = glm::vec3(0, 0, 1);  // a face with no area at all: any finite answer will do
    return point;
}

float DisplacedSurface::height(int face, float u, float v) const {
    return maps_.hasDisplacement() ? sampleBilinear(maps_.layout, maps_.displacement, 1, 0, face, u, v) : 0.0f;
}

// Central differences half a map cell wide, across tile borders too: the slope and the shading
// normal agree on both sides of a face edge (surface/texel_layout.h).
glm::vec2 DisplacedSurface::heightGradient(int face, float u, float v) const {
    if (!maps_.hasDisplacement()) return glm::vec2(0.0f);
    return slopeAcrossTiles(maps_.layout, maps_.displacement, face, u, v);
}

SurfaceVertex DisplacedSurface::at(int face, float u, float v) const {
    const LimitPoint p = limitPoint(face, u, v);
    const float d = height(face, u, v);
    const glm::vec2 slope = maps_.shadingNormal == ShadingNormal::Limit ? glm::vec2(0.0f) : heightGradient(face, u, v);

    // The displaced surface P + d·N has derivatives Pu + d_u·N + d·N_u; the curvature term
    // d·N_u is dropped (it vanishes for flat patches and is small for the displacements a fit
    // produces). Its dot with N is |Pu × Pv| > 0, so the normal never flips.
    const glm::vec3 du = p.dPdu + slope.x * p.normal, dv = p.dPdv + slope.y * p.normal;
    const glm::vec3 normal = direction(glm::cross(du, dv), lengthProduct(du, dv)).value_or(p.normal);

    // Tangent along dP/du in the normal's plane; at a collapsed dP/du, cross(dP/dv, N) points the
    // same way (for a right-handed frame), and failing both any perpendicular keeps it finite.
    const float scale = glm::length(p.dPdu) + glm::length(p.dPdv);
    std::optional<glm::vec3> tangent = direction(p.dPdu - glm::dot(p.dPdu, normal) * normal, scale);
    if (!tangent) tangent = direction(glm::cross(p.dPdv, normal), scale);
    if (!tangent) tangent = anyPerpendicular(normal);
    const float handedness = glm::dot(glm::cross(normal, *tangent), p.dPdv) < 0.0f ? -1.0f : 1.0f;

    return {p.position + d * p.normal, normal, glm::vec4(*tangent, handedness), du, dv};
}

}  // namespace subdfit::surface
