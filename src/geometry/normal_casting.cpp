#include "geometry/normal_casting.h"

#include <glm/geometric.hpp>

#include "util/error.h"

namespace subdfit::geometry {

NormalCasts castAlongNormals(const SurfaceQueries& surface, std::span<const glm::vec3> origins,
                             std::span<const glm::vec3> normals, float reach, float detour, std::optional<float> facing) {
    SUBDFIT_CHECK(origins.size() == normals.size());
    NormalCasts casts;
    casts.hits.resize(origins.size());
    double agreement = 0.0;
    for (size_t k = 0; k < origins.size(); ++k) {
        if (glm::dot(normals[k], normals[k]) == 0.0f) continue;
        casts.hits[k] = surface.castBothWays(origins[k], normals[k], reach);
        if (!casts.hits[k]) continue;
        const glm::vec3 faced = surface.triangleNormal(casts.hits[k]->triangle);
        if (const float area = glm::length(faced); area > 0.0f) agreement += glm::dot(faced / area, normals[k]);
    }
    casts.facing = facing ? *facing : agreement >= 0.0 ? 1.0f : -1.0f;
    for (size_t k = 0; k < origins.size(); ++k) {
        auto& hit = casts.hits[k];
        if (!hit) continue;
        if (casts.facing * glm::dot(surface.triangleNormal(hit->triangle), normals[k]) <= 0.0f)
            hit = surface.castFacing(origins[k], normals[k], reach, casts.facing);
        if (hit && !surface.reachesNearest(origins[k], *hit, detour)) hit.reset();
    }
    return casts;
}

}  // namespace subdfit::geometry
