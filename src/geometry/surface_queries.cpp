#include "geometry/surface_queries.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <limits>

#include "util/error.h"

namespace subdfit::geometry {
namespace {

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
glm::vec3 closestOnTriangle(const glm::vec3& p, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 ab = b - a, ac = c - a, ap = p - a;
    const float d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return a;
    const glm::vec3 bp = p - b;
    const float d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return b;
    const float vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + ab * (d1 / (d1 - d3));
    const glm::vec3 cp = p - c;
    const float d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return c;
    const float vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + ac * (d2 / (d2 - d6));
    const float va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    const float denom = va + vb + vc;
    if (!(denom > 0)) return a;  // degenerate triangle
    return a + ab * (vb / denom) + ac * (vc / denom);
}

// Embree visits the triangles whose bounds reach within the query radius; each one that is
// nearer shrinks the radius, so the search ends at the nearest.
bool visitTriangle(RTCPointQueryFunctionArguments* args) {
    const auto& mesh = *static_cast<const mesh::PolygonMesh*>(args->userPtr);
    const glm::vec3 p(args->query->x, args->query->y, args->query->z);
    const int* f = &mesh.faceIndices[3 * size_t(args->primID)];
    const float d = glm::length(p - closestOnTriangle(p, mesh.positions[size_t(f[0])], mesh.positions[size_t(f[1])],
                                                      mesh.positions[size_t(f[2])]));
    if (d >= args->query->radius) return false;
    args->query->radius = d;
    return true;
}

}  // namespace

struct SurfaceQueries::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

SurfaceQueries::SurfaceQueries(const mesh::PolygonMesh& triangles)
    : mesh_(triangles), embree_(std::make_unique<Embree>()) {
    for (int size : triangles.faceSizes) SUBDFIT_CHECK(size == 3);
    embree_->device = rtcNewDevice(nullptr);
    if (!embree_->device) throw Error("Embree could not create a device");
    embree_->scene = rtcNewScene(embree_->device);
    // Watertight: a ray through a shared edge or vertex must not slip between the triangles
    // (bake rays from symmetric cages do exactly that).
    rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry geometry = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), triangles.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), size_t(triangles.faceCount())));
    for (size_t v = 0; v < triangles.positions.size(); ++v)
        for (int c = 0; c < 3; ++c) vertices[3 * v + size_t(c)] = triangles.positions[v][c];
    for (size_t i = 0; i < triangles.faceIndices.size(); ++i) indices[i] = unsigned(triangles.faceIndices[i]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(embree_->scene);
}

SurfaceQueries::~SurfaceQueries() = default;

std::optional<RayHit> SurfaceQueries::cast(const glm::vec3& origin, const glm::vec3& direction,
                                           float maxDistance) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray.org_x = origin.x, query.ray.org_y = origin.y, query.ray.org_z = origin.z;
    query.ray.dir_x = direction.x, query.ray.dir_y = direction.y, query.ray.dir_z = direction.z;
    query.ray.tnear = 0.0f;
    query.ray.tfar = maxDistance;
    query.ray.mask = ~0u;
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return RayHit{query.ray.tfar, int(query.hit.primID), query.hit.u, query.hit.v};
}

float SurfaceQueries::closestDistance(const glm::vec3& point) const {
    RTCPointQuery query{};
    query.x = point.x, query.y = point.y, query.z = point.z;
    query.radius = std::numeric_limits<float>::infinity();
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(embree_->scene, &query, &context, visitTriangle, const_cast<mesh::PolygonMesh*>(&mesh_));
    return query.radius;
}

std::optional<RayHit> SurfaceQueries::castBothWays(const glm::vec3& origin, const glm::vec3& direction,
                                                   float maxDistance) const {
    auto ahead = cast(origin, direction, maxDistance);
    auto behind = cast(origin, -direction, ahead ? ahead->distance : maxDistance);
    if (behind) {
        behind->distance = -behind->distance;
        return behind;
    }
    return ahead;
}

std::optional<RayHit> SurfaceQueries::castFacing(const glm::vec3& origin, const glm::vec3& direction, float maxDistance,
                                                 float facing) const {
    constexpr int kSheets = 4;  // sheets passed through per direction before giving up
    std::optional<RayHit> best;
    for (const float way : {1.0f, -1.0f}) {
        float travelled = 0.0f;
        for (int sheet = 0; sheet < kSheets; ++sheet) {
            const float reach = (best ? std::abs(best->distance) : maxDistance) - travelled;
            if (reach <= 0.0f) break;
            auto hit = cast(origin + way * travelled * direction, way * direction, reach);
            if (!hit) break;
            travelled += hit->distance;
            if (facing * glm::dot(triangleNormal(hit->triangle), direction) > 0.0f) {
                hit->distance = way * travelled;
                best = hit;
                break;
            }
            travelled += 1e-6f * maxDistance;  // past the sheet
        }
    }
    return best;
}

bool SurfaceQueries::reachesNearest(const glm::vec3& origin, const RayHit& hit, float detour) const {
    const float nearest = closestDistance(origin);
    return std::abs(hit.distance) <= std::max(2.0f * nearest, nearest + detour) * (1.0f + 1e-4f) + 1e-7f;
}

glm::vec3 SurfaceQueries::triangleNormal(int t) const {
    auto p = [&](int k) { return mesh_.positions[size_t(mesh_.faceIndices[size_t(3 * t + k)])]; };
    return glm::cross(p(1) - p(0), p(2) - p(0));
}

}  // namespace subdfit::geometry
