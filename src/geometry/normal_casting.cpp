#include "geometry/normal_casting.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <numeric>
#include <vector>

#include "util/error.h"

namespace subdfit::geometry {

NormalCasts castAlongNormals(const SurfaceQueries& surface, std::span<const glm::vec3> origins,
                             std::span<const glm::vec3> normals, float reach, float detour,
                             std::optional<float> facing) {
    SUBDFIT_CHECK(origins.size() == normals.size());
    NormalCasts casts;
    casts.hits.resize(origins.size());
    // Each ray on its own (the queries are thread-safe); the sum keeps its order, so the result
    // does not depend on the threads.
    std::vector<double> agreement(origins.size(), 0.0);
    tbb::parallel_for(size_t(0), origins.size(), [&](size_t k) {
        if (glm::dot(normals[k], normals[k]) == 0.0f) return;
        casts.hits[k] = surface.castBothWays(origins[k], normals[k], reach);
        if (!casts.hits[k]) return;
        const glm::vec3 faced = surface.triangleNormal(casts.hits[k]->triangle);
        if (const float area = glm::length(faced); area > 0.0f) agreement[k] = glm::dot(faced / area, normals[k]);
    });
    casts.facing = facing ? *facing : std::accumulate(agreement.begin(), agreement.end(), 0.0) >= 0.0 ? 1.0f : -1.0f;
    tbb::parallel_for(size_t(0), origins.size(), [&](size_t k) {
        auto& hit = casts.hits[k];
        if (!hit) return;
        if (casts.facing * glm::dot(surface.triangleNormal(hit->triangle), normals[k]) <= 0.0f)
            hit = surface.castFacing(origins[k], normals[k], reach, casts.facing);
        if (hit && !surface.reachesNearest(origins[k], *hit, detour)) hit.reset();
    });
    return casts;
}

}  // namespace subdfit::geometry
