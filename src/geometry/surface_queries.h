#pragma once
// Ray and closest-point queries against a triangle mesh, by Embree (one BVH for both): the bake
// casts along a cage's limit normal to find the reference surface, as a texture baker does, and
// the surface distance asks for the exact nearest point.
#include <glm/vec3.hpp>

#include <memory>
#include <optional>

#include "mesh/polygon_mesh.h"

namespace subdfit::geometry {

struct RayHit {
    float distance = 0.0f;  // along the (unit) direction
    int triangle = -1;
    float u = 0.0f, v = 0.0f;  // barycentrics: the point is (1−u−v)·p0 + u·p1 + v·p2
};

class SurfaceQueries {
public:
    // `triangles`: a triangulated mesh; kept by reference for hit lookups, so it must outlive this.
    explicit SurfaceQueries(const mesh::PolygonMesh& triangles);
    ~SurfaceQueries();
    SurfaceQueries(const SurfaceQueries&) = delete;
    SurfaceQueries& operator=(const SurfaceQueries&) = delete;

    // The first hit along the unit `direction` within (0, maxDistance], either side of any
    // triangle. Thread-safe.
    std::optional<RayHit> cast(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const;

    // The nearer of the hits along +direction and −direction (distance signed accordingly).
    std::optional<RayHit> castBothWays(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const;

    // As castBothWays, but only hits on triangles that face the way `facing` says (+1: along
    // `direction`, as the surface the ray leaves), passing through up to a few sheets that face
    // the other way. A surface inside a thin part (an ear, a fin) lies between two sheets of the
    // mesh; the nearer may be the far side, and taking it would fold the surface through itself.
    std::optional<RayHit> castFacing(const glm::vec3& origin, const glm::vec3& direction, float maxDistance,
                                     float facing) const;

    // Whether `hit`, cast from `origin`, found (about) the nearest part of the mesh: it is no
    // farther than twice the distance to the nearest point, or than `detour` beyond it. A ray that
    // grazes past the nearest surface and lands on another part (the next leg, the far wall of
    // a fold) did not; one that finds a trough beside a nearer crest of the same relief did.
    bool reachesNearest(const glm::vec3& origin, const RayHit& hit, float detour = 0.0f) const;

    // (p1 − p0) × (p2 − p0) of triangle t: its winding's normal, twice its area long.
    glm::vec3 triangleNormal(int t) const;

    // The distance from `point` to the nearest point of the mesh (exact; infinity for a mesh
    // without triangles). Thread-safe.
    float closestDistance(const glm::vec3& point) const;

    const mesh::PolygonMesh& mesh() const { return mesh_; }

private:
    struct Embree;
    const mesh::PolygonMesh& mesh_;
    std::unique_ptr<Embree> embree_;
};

}  // namespace subdfit::geometry
