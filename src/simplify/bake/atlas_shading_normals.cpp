#include "simplify/bake/atlas_shading_normals.h"

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

#include "mesh/mesh_geometry.h"
#include "surface/displaced_surface.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

// Points per texel side at which both surfaces are compared (their frames vary smoothly; the
// reference's changes from triangle to triangle, which a few points average).
constexpr int kSamples = 2;

// The reference's triangles by where they lie in texture space: a grid × grid bucket grid over
// [0, 1]², each triangle in every bucket its coordinates' bounding box touches.
class UvTriangleGrid {
public:
    UvTriangleGrid(const mesh::PolygonMesh& reference, int grid)
        : reference_(reference), grid_(grid), buckets_(size_t(grid) * size_t(grid)) {
        for (int f = 0; f < reference.faceCount(); ++f) {
            glm::vec2 lo(1e30f), hi(-1e30f);
            for (int k = 0; k < 3; ++k) {
                const glm::vec2 t = uv(f, k);
                lo = glm::min(lo, t), hi = glm::max(hi, t);
            }
            for (int y = cell(lo.y); y <= cell(hi.y); ++y)
                for (int x = cell(lo.x); x <= cell(hi.x); ++x)
                    buckets_[size_t(y) * size_t(grid_) + size_t(x)].push_back(f);
        }
    }

    glm::vec2 uv(int face, int corner) const {
        return reference_.uvs[size_t(reference_.faceIndices[size_t(3 * face + corner)])];
    }
    const std::vector<int>& near(glm::vec2 uv) const {
        return buckets_[size_t(cell(uv.y)) * size_t(grid_) + size_t(cell(uv.x))];
    }

private:
    int cell(float t) const { return std::clamp(int(std::floor(t * float(grid_))), 0, grid_ - 1); }

    const mesh::PolygonMesh& reference_;
    int grid_;
    std::vector<std::vector<int>> buckets_;
};

// The barycentric coordinates (of corners 1 and 2) of `p` in the triangle a, b, c, if it lies
// inside (with a little slack for the shared edges).
std::optional<glm::vec2> barycentric(glm::vec2 p, glm::vec2 a, glm::vec2 b, glm::vec2 c) {
    const glm::vec2 e1 = b - a, e2 = c - a, d = p - a;
    const float det = e1.x * e2.y - e1.y * e2.x;
    if (!(std::abs(det) > 0.0f)) return std::nullopt;
    const float s = (d.x * e2.y - d.y * e2.x) / det, t = (e1.x * d.y - e1.y * d.x) / det;
    constexpr float slack = 1e-5f;
    if (s < -slack || t < -slack || s + t > 1.0f + slack) return std::nullopt;
    return glm::vec2(s, t);
}

// Where the bilinear map of a ptex face's corner coordinates reaches `uv`, if it does: Newton
// from the face's centre.
std::optional<glm::vec2> inverseBilinear(const glm::vec2* c, glm::vec2 uv) {
    glm::vec2 st(0.5f);
    for (int iteration = 0; iteration < 12; ++iteration) {
        const glm::vec2 at = glm::mix(glm::mix(c[0], c[1], st.x), glm::mix(c[3], c[2], st.x), st.y);
        const glm::vec2 ds = glm::mix(c[1] - c[0], c[2] - c[3], st.y), dt = glm::mix(c[3] - c[0], c[2] - c[1], st.x);
        const float det = ds.x * dt.y - ds.y * dt.x;
        if (!(std::abs(det) > 1e-14f)) return std::nullopt;
        const glm::vec2 r = at - uv;
        const glm::vec2 step((r.x * dt.y - r.y * dt.x) / det, (ds.x * r.y - ds.y * r.x) / det);
        st -= step;
        if (!(std::abs(st.x) < 4.0f && std::abs(st.y) < 4.0f)) return std::nullopt;
        if (glm::dot(step, step) < 1e-12f) {
            constexpr float slack = 1e-4f;
            if (st.x < -slack || st.y < -slack || st.x > 1.0f + slack || st.y > 1.0f + slack) return std::nullopt;
            return glm::clamp(st, 0.0f, 1.0f);
        }
    }
    return std::nullopt;
}

// What a texel (x, y, z) of a normal texture means, and back: rgb in [0, 1] ↔ a unit vector.
glm::vec3 decode(const float* rgb) {
    const glm::vec3 t = glm::vec3(rgb[0], rgb[1], rgb[2]) * 2.0f - 1.0f;
    return glm::length(t) > 1e-6f ? glm::normalize(t) : glm::vec3(0, 0, 1);
}

}  // namespace

std::optional<glm::mat3> normalTextureFrame(glm::vec3 dp1, glm::vec3 dp2, glm::vec2 duv1, glm::vec2 duv2,
                                            glm::vec3 normal) {
    // T·dp1 = det·du1 and T·dp2 = det·du2 with T ⟂ N (likewise B for v), det = N·(dp1 × dp2):
    // the shader's cotangent vectors. Dividing by det makes them the gradients whatever way
    // dp1, dp2 turn, as a rasterizer's screen axes always turn the same way about a normal
    // that faces the eye.
    const float det = glm::dot(normal, glm::cross(dp1, dp2));
    const float size = glm::length(dp1) * glm::length(dp2);
    if (!(std::abs(det) > 1e-6f * size)) return std::nullopt;
    const glm::vec3 across2 = glm::cross(dp2, normal), across1 = glm::cross(normal, dp1);
    const glm::vec3 gradU = (across2 * duv1.x + across1 * duv2.x) / det;
    const glm::vec3 gradV = (across2 * duv1.y + across1 * duv2.y) / det;
    const float scale = std::max(glm::length(gradU), glm::length(gradV));
    if (!(scale > 0.0f) || !std::isfinite(scale)) return std::nullopt;
    const glm::mat3 frame(gradU / scale, -gradV / scale, normal);
    // Coordinates that barely turn across the surface give a frame with no inverse.
    if (!(std::abs(glm::determinant(frame)) > 1e-3f)) return std::nullopt;
    return frame;
}

namespace {

// The reference as the atlas's texels see it: its shading normals and its triangles by where they
// lie in texture space.
struct ReferenceInAtlas {
    const mesh::PolygonMesh& mesh;
    std::vector<glm::vec3> normals;
    UvTriangleGrid triangles;
};

// A point of the reference: its normal texture's frame and its shading normal.
struct ReferencePoint {
    glm::mat3 frame;
    glm::vec3 normal;
};

// The reference's point at `uv` nearest to `position`, within `maxDistance` (a mirrored atlas
// maps two places of the reference to one texel).
std::optional<ReferencePoint> nearestAt(const ReferenceInAtlas& reference, glm::vec2 uv, glm::vec3 position,
                                        float maxDistance) {
    const mesh::PolygonMesh& mesh = reference.mesh;
    const UvTriangleGrid& triangles = reference.triangles;
    float nearest = maxDistance;
    std::optional<ReferencePoint> found;
    for (int f : triangles.near(uv)) {
        const auto b = barycentric(uv, triangles.uv(f, 0), triangles.uv(f, 1), triangles.uv(f, 2));
        if (!b) continue;
        auto vertex = [&](int k) { return size_t(mesh.faceIndices[size_t(3 * f + k)]); };
        const glm::vec3 p0 = mesh.positions[vertex(0)], p1 = mesh.positions[vertex(1)], p2 = mesh.positions[vertex(2)];
        const float distance = glm::length(p0 + b->x * (p1 - p0) + b->y * (p2 - p0) - position);
        if (!(distance < nearest)) continue;
        glm::vec3 n = (1.0f - b->x - b->y) * reference.normals[vertex(0)] + b->x * reference.normals[vertex(1)] +
                      b->y * reference.normals[vertex(2)];
        if (!(glm::length(n) > 1e-6f)) continue;
        n = glm::normalize(n);
        const auto frame = normalTextureFrame(p1 - p0, p2 - p0, triangles.uv(f, 1) - triangles.uv(f, 0),
                                              triangles.uv(f, 2) - triangles.uv(f, 0), n);
        if (!frame) continue;
        nearest = distance;
        found = ReferencePoint{*frame, n};
    }
    return found;
}

// The unit vector that, in the cage's normal texture frame at `ours` (at `st` of the ptex face
// whose corner coordinates are `c`), shades as the reference's texel `rgb` does at `point`.
std::optional<glm::vec3> carriedDirection(const surface::SurfaceVertex& ours, const glm::vec2* c, glm::vec2 st,
                                          const ReferencePoint& point, const float* rgb) {
    // Renderers turn a normal towards the eye before the texture tilts it, and the frame's third
    // column turns with it: shade the cage from the side the reference's author faces (the cage
    // may be wound the other way).
    const glm::vec3 ourNormal = glm::dot(ours.normal, point.normal) < 0.0f ? -ours.normal : ours.normal;
    const glm::vec2 duvds = glm::mix(c[1] - c[0], c[2] - c[3], st.y), duvdt = glm::mix(c[3] - c[0], c[2] - c[1], st.x);
    const auto ourFrame = normalTextureFrame(ours.dPdu, ours.dPdv, duvds, duvdt, ourNormal);
    if (!ourFrame) return std::nullopt;
    const glm::vec3 shading = glm::normalize(point.frame * decode(rgb));
    const glm::vec3 t = glm::inverse(*ourFrame) * shading;
    if (!(glm::length(t) > 1e-6f) || !std::isfinite(t.x + t.y + t.z)) return std::nullopt;
    return glm::normalize(t);
}

// Each texel with a direction summed into it takes their mean, tilted no further than a normal
// texture can (not past the surface's own plane). Returns which did.
std::vector<char> writeCarried(const std::vector<glm::vec3>& sum, std::vector<float>& texels) {
    std::vector<char> carried(sum.size(), 0);
    for (size_t texel = 0; texel < sum.size(); ++texel) {
        if (!(glm::length(sum[texel]) > 1e-6f)) continue;
        glm::vec3 t = glm::normalize(sum[texel]);
        t.z = std::max(t.z, 0.1f);
        t = glm::normalize(t);
        for (int k = 0; k < 3; ++k) texels[3 * texel + size_t(k)] = t[k] * 0.5f + 0.5f;
        carried[texel] = 1;
    }
    return carried;
}

}  // namespace

std::vector<char> carryShadingNormals(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                                      const mesh::PolygonMesh& reference, float maxDistance,
                                      std::vector<float>& texels) {
    const surface::AppearanceAtlas& atlas = maps.appearanceAtlas;
    const int size = atlas.size;
    SUBDFIT_CHECK(size >= 2 && texels.size() == 3 * size_t(size) * size_t(size));
    SUBDFIT_CHECK(!reference.uvs.empty() && reference.faceCount() * 3 == int(reference.faceIndices.size()));
    const ReferenceInAtlas inAtlas{reference, mesh::shadingNormals(reference), UvTriangleGrid(reference, size)};
    const surface::DisplacedSurface surface(cage, maps);
    SUBDFIT_CHECK(atlas.cornerUvs.size() == 4 * size_t(surface.ptexFaceCount()));

    const int grid = size * kSamples;
    std::vector<glm::vec3> sum(size_t(size) * size_t(size), glm::vec3(0.0f));
    for (int face = 0; face < surface.ptexFaceCount(); ++face) {
        if (!surface.hasSurface(face)) continue;
        const glm::vec2* c = &atlas.cornerUvs[4 * size_t(face)];
        const glm::vec2 lo = glm::min(glm::min(c[0], c[1]), glm::min(c[2], c[3])) * float(grid) - 0.5f;
        const glm::vec2 hi = glm::max(glm::max(c[0], c[1]), glm::max(c[2], c[3])) * float(grid) - 0.5f;
        for (int y = std::max(int(std::ceil(lo.y)), 0); y <= std::min(int(std::floor(hi.y)), grid - 1); ++y)
            for (int x = std::max(int(std::ceil(lo.x)), 0); x <= std::min(int(std::floor(hi.x)), grid - 1); ++x) {
                const glm::vec2 uv((float(x) + 0.5f) / float(grid), (float(y) + 0.5f) / float(grid));
                const auto st = inverseBilinear(c, uv);
                if (!st) continue;
                const surface::SurfaceVertex ours = surface.at(face, st->x, st->y);
                const auto point = nearestAt(inAtlas, uv, ours.position, maxDistance);
                if (!point) continue;
                const size_t texel = size_t(y / kSamples) * size_t(size) + size_t(x / kSamples);
                if (const auto t = carriedDirection(ours, c, *st, *point, &texels[3 * texel])) sum[texel] += *t;
            }
    }
    return writeCarried(sum, texels);
}

}  // namespace subdfit::simplify
