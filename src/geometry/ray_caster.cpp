#include "geometry/ray_caster.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

#include "util/error.h"

namespace subdfit::geometry {

struct RayCaster::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

RayCaster::RayCaster(const mesh::PolygonMesh& triangles) : mesh_(triangles), embree_(std::make_unique<Embree>()) {
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
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), size_t(triangles.faceCount())));
    for (size_t v = 0; v < triangles.positions.size(); ++v)
        for (int c = 0; c < 3; ++c) vertices[3 * v + size_t(c)] = triangles.positions[v][c];
    for (size_t i = 0; i < triangles.faceIndices.size(); ++i) indices[i] = unsigned(triangles.faceIndices[i]);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(embree_->scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(embree_->scene);
}

RayCaster::~RayCaster() = default;

std::optional<RayHit> RayCaster::cast(const glm::vec3& origin, const glm::vec3& direction, float maxDistance) const {
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

std::optional<RayHit> RayCaster::castBothWays(const glm::vec3& origin, const glm::vec3& direction,
                                              float maxDistance) const {
    auto ahead = cast(origin, direction, maxDistance);
    auto behind = cast(origin, -direction, ahead ? ahead->distance : maxDistance);
    if (behind) {
        behind->distance = -behind->distance;
        return behind;
    }
    return ahead;
}

}  // namespace subdfit::geometry
