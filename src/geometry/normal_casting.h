#pragma once
// Casting from a surface to a reference mesh along the surface's normals, as a texture baker
// does: how the bake finds each map node's height and material, and the limit fit where each
// sample of the cage's surface should be.
#include <glm/vec3.hpp>

#include <optional>
#include <span>
#include <vector>

#include "geometry/surface_queries.h"

namespace subdfit::geometry {

struct NormalCasts {
    std::vector<std::optional<RayHit>> hits;  // one per origin; distance signed along the normal
    float facing = 1.0f;                      // +1: the reference faces the way the normals point
};

// From each origin along ± its unit normal (a zero normal casts nothing), within `reach`: the
// nearest hit on a sheet that faces as `facing` says (by default as most nearest hits say: the
// reference may wind either way). Nearer sheets facing the other way (the far side of a thin
// part: taking them would fold the surface through itself) are passed through, and a hit is
// kept only when it reaches about the nearest part of the reference
// (SurfaceQueries::reachesNearest with `detour`).
NormalCasts castAlongNormals(const SurfaceQueries& surface, std::span<const glm::vec3> origins,
                             std::span<const glm::vec3> normals, float reach, float detour,
                             std::optional<float> facing = std::nullopt);

}  // namespace subdfit::geometry
