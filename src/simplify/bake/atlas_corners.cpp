#include "simplify/bake/atlas_corners.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "geometry/normal_casting.h"
#include "geometry/surface_queries.h"
#include "subdiv/limit_evaluator.h"
#include "surface/appearance_atlas.h"
#include "surface/texel_layout.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

// Samples per grid side on each ptex face whose hits place its corners (corners included).
constexpr int kGrid = 4;

// Solves the 4×4 system m x = b in place (partial pivoting); false when singular.
bool solve4(std::array<std::array<double, 4>, 4> m, std::array<glm::dvec2, 4>& b) {
    for (int c = 0; c < 4; ++c) {
        int pivot = c;
        for (int r = c + 1; r < 4; ++r)
            if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
        if (std::abs(m[pivot][c]) < 1e-12) return false;
        std::swap(m[c], m[pivot]);
        std::swap(b[c], b[pivot]);
        for (int r = 0; r < 4; ++r) {
            if (r == c) continue;
            const double f = m[r][c] / m[c][c];
            for (int k = c; k < 4; ++k) m[r][k] -= f * m[c][k];
            b[r] -= f * b[c];
        }
    }
    for (int c = 0; c < 4; ++c) b[c] /= m[c][c];
    return true;
}

// Bilinear weights of ptex (u, v) on the corners (0, 0), (1, 0), (1, 1), (0, 1).
std::array<double, 4> cornerWeights(double u, double v) { return {(1 - u) * (1 - v), u * (1 - v), u * v, (1 - u) * v}; }

struct Hit {
    glm::vec3 point;
    glm::vec2 uv;
    float uvPerLength;  // of the reference triangle hit: how fast its texture coordinates change
};

// The hits of one face that agree with one another: grid neighbours whose coordinates differ by
// no more than their distance apart allows (a seam of the atlas runs between those that do not),
// the largest such connected set.
std::vector<int> agreeingHits(const std::array<std::optional<Hit>, kGrid * kGrid>& hits) {
    std::array<int, kGrid * kGrid> component;
    component.fill(-1);
    std::vector<std::vector<int>> components;
    for (int start = 0; start < kGrid * kGrid; ++start) {
        if (!hits[size_t(start)] || component[size_t(start)] >= 0) continue;
        std::vector<int> members{start};
        component[size_t(start)] = int(components.size());
        for (size_t k = 0; k < members.size(); ++k) {
            const int a = members[k], ai = a % kGrid, aj = a / kGrid;
            for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
                const int bi = ai + di, bj = aj + dj, b = bj * kGrid + bi;
                if (bi < 0 || bj < 0 || bi >= kGrid || bj >= kGrid || !hits[size_t(b)] || component[size_t(b)] >= 0)
                    continue;
                const Hit &p = *hits[size_t(a)], &q = *hits[size_t(b)];
                const float allowed =
                    3.0f * std::max(p.uvPerLength, q.uvPerLength) * glm::distance(p.point, q.point) + 1e-4f;
                if (glm::distance(p.uv, q.uv) > allowed) continue;
                component[size_t(b)] = int(components.size());
                members.push_back(b);
            }
        }
        components.push_back(std::move(members));
    }
    if (components.empty()) return {};
    return *std::max_element(components.begin(), components.end(),
                             [](const auto& a, const auto& b) { return a.size() < b.size(); });
}

// The corners' coordinates that best give the agreeing hits' coordinates by bilinear blending,
// held towards their mean where the hits leave a corner undetermined.
std::array<glm::vec2, 4> fitCorners(const std::array<std::optional<Hit>, kGrid * kGrid>& hits,
                                    const std::vector<int>& use) {
    std::array<std::array<double, 4>, 4> m{};
    std::array<glm::dvec2, 4> b{};
    glm::dvec2 mean(0.0);
    for (int k : use) mean += glm::dvec2(hits[size_t(k)]->uv);
    mean /= double(use.size());
    for (int k : use) {
        const auto w = cornerWeights(double(k % kGrid) / (kGrid - 1), double(k / kGrid) / (kGrid - 1));
        for (int r = 0; r < 4; ++r) {
            for (int c = 0; c < 4; ++c) m[r][c] += w[size_t(r)] * w[size_t(c)];
            b[size_t(r)] += w[size_t(r)] * glm::dvec2(hits[size_t(k)]->uv);
        }
    }
    const double ridge = 1e-3;
    for (int r = 0; r < 4; ++r) {
        m[r][r] += ridge;
        b[size_t(r)] += ridge * mean;
    }
    std::array<glm::vec2, 4> corners;
    if (!solve4(m, b)) {
        corners.fill(glm::vec2(mean));
        return corners;
    }
    for (int c = 0; c < 4; ++c)
        corners[size_t(c)] = glm::clamp(glm::vec2(b[size_t(c)]), glm::vec2(-1.0f), glm::vec2(2.0f));
    return corners;
}

// Corners that meet at one limit point and whose coordinates agree become one: the texture is
// then continuous across the faces' shared edges inside a chart, and split where they do not
// agree (a seam of the atlas).
void weldCorners(const mesh::PolygonMesh& cage, std::vector<glm::vec2>& corners, const std::vector<char>& found) {
    const surface::TexelLayout points = surface::buildTexelLayout(cage, 1);
    struct Cluster {
        glm::vec2 sum{0.0f};
        int count = 0;
        glm::vec2 centre() const { return sum / float(count); }
    };
    std::vector<std::vector<Cluster>> clusters(size_t(points.nodeCount));
    std::vector<std::pair<int, int>> member(corners.size(), {-1, -1});  // (node, cluster)
    for (int f = 0; f < points.ptexFaceCount; ++f) {
        if (!found[size_t(f)]) continue;
        float extent = 0.0f;
        for (int k = 1; k < 4; ++k)
            extent = std::max(extent, glm::distance(corners[4 * size_t(f)], corners[4 * size_t(f) + size_t(k)]));
        const float tolerance = 0.25f * extent + 1e-5f;
        for (int k = 0; k < 4; ++k) {
            const int node = surface::cornerPoint(points, f, k);
            const glm::vec2 uv = corners[4 * size_t(f) + size_t(k)];
            auto& here = clusters[size_t(node)];
            int c = 0;
            while (c < int(here.size()) && glm::distance(here[size_t(c)].centre(), uv) > tolerance) ++c;
            if (c == int(here.size())) here.emplace_back();
            here[size_t(c)].sum += uv;
            ++here[size_t(c)].count;
            member[4 * size_t(f) + size_t(k)] = {node, c};
        }
    }
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            glm::vec2& uv = corners[4 * size_t(f) + size_t(k)];
            if (const auto [node, c] = member[4 * size_t(f) + size_t(k)]; node >= 0) {
                uv = clusters[size_t(node)][size_t(c)].centre();
                continue;
            }
            // A face no ray placed takes what its corners' neighbours agreed on.
            const int node = surface::cornerPoint(points, f, k);
            uv = clusters[size_t(node)].empty() ? glm::vec2(0.5f) : clusters[size_t(node)].front().centre();
        }
}

// An n-gon's sub-faces (n ≠ 4) meet at its edges' midpoints, corners (1, 0) and (0, 1), and at
// its centre, corner (1, 1); inside a chart the texture there is about the mean of the face's
// vertices' (corner (0, 0) of each sub-face), which is what the AUVS coding predicts. A value
// that every corner holding it puts within a small part of its sub-face of that mean becomes
// the mean: the fit's noise, not the texture, is what would have cost the bytes.
void snapToVertexMeans(const mesh::PolygonMesh& cage, std::vector<glm::vec2>& corners) {
    constexpr float kTolerance = 0.15f;  // of the sub-face's extent in the atlas
    const surface::TexelLayout points = surface::buildTexelLayout(cage, 1);
    struct Value {
        glm::vec2 uv;
        glm::vec2 predictions{0.0f};
        int count = 0;
        bool movable = true;
    };
    std::vector<std::vector<Value>> values(size_t(points.nodeCount));
    auto valueAt = [&](int f, int k) -> Value& {
        auto& list = values[size_t(surface::cornerPoint(points, f, k))];
        const glm::vec2 uv = corners[4 * size_t(f) + size_t(k)];
        auto at = std::find_if(list.begin(), list.end(), [&](const Value& v) { return v.uv == uv; });
        return at != list.end() ? *at : list.emplace_back(Value{uv});
    };
    int ptex = 0;
    for (const int n : cage.faceSizes) {
        const int first = ptex;
        ptex += n == 4 ? 1 : n;
        if (n == 4) {
            for (int k = 0; k < 4; ++k) valueAt(first, k).movable = false;
            continue;
        }
        auto vertex = [&](int i) { return corners[4 * size_t(first + (i % n + n) % n)]; };
        glm::vec2 centre(0.0f);
        for (int i = 0; i < n; ++i) centre += vertex(i) / float(n);
        for (int i = 0; i < n; ++i) {
            const int f = first + i;
            float extent = 0.0f;
            for (int k = 1; k < 4; ++k)
                extent = std::max(extent, glm::distance(corners[4 * size_t(f)], corners[4 * size_t(f) + size_t(k)]));
            valueAt(f, 0).movable = false;
            for (const auto& [k, prediction] :
                 {std::pair{1, 0.5f * (vertex(i) + vertex(i + 1))}, std::pair{3, 0.5f * (vertex(i - 1) + vertex(i))},
                  std::pair{2, centre}}) {
                Value& value = valueAt(f, k);
                value.movable = value.movable && glm::distance(value.uv, prediction) <= kTolerance * extent;
                value.predictions += prediction;
                ++value.count;
            }
        }
    }
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            const Value& value = valueAt(f, k);
            if (value.movable && value.count > 0)
                corners[4 * size_t(f) + size_t(k)] = value.predictions / float(value.count);
        }
}

}  // namespace

std::vector<glm::vec2> atlasCornerUvs(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                                      float maxDistance) {
    const subdiv::LimitEvaluator limit(cage);
    const std::vector<glm::dvec3> limitPoints = limit.patchPoints(cage.positions);
    const int faces = limit.ptexFaceCount();
    // Sized, not constructed with the size: GCC 12 misreads the latter's release (-Wfree-nonheap-object).
    std::vector<glm::vec3> origins, normals;
    origins.resize(size_t(faces) * kGrid * kGrid);
    normals.resize(origins.size(), glm::vec3(0.0f));
    for (int f = 0; f < faces; ++f) {
        if (f % 1024 == 0) throwIfStopRequested();
        if (!limit.hasSurface(f, 0.5f, 0.5f)) continue;
        for (int k = 0; k < kGrid * kGrid; ++k) {
            // A hair inside the face: the derivatives vanish at some extraordinary corners.
            const glm::vec2 uv =
                glm::mix(glm::vec2(float(k % kGrid), float(k / kGrid)) / float(kGrid - 1), glm::vec2(0.5f), 1e-3f);
            const subdiv::LimitSample s = limit.evaluate(f, uv.x, uv.y, limitPoints);
            const glm::vec3 n = glm::cross(s.dPdu, s.dPdv);
            origins[size_t(f) * kGrid * kGrid + size_t(k)] = s.position;
            if (glm::length(n) > 1e-20f) normals[size_t(f) * kGrid * kGrid + size_t(k)] = glm::normalize(n);
        }
    }
    const geometry::SurfaceQueries surface(reference);
    const geometry::NormalCasts casts =
        geometry::castAlongNormals(surface, origins, normals, maxDistance, 0.25f * maxDistance);
    auto texcoord = [&](int triangle, float u, float v) {
        auto at = [&](int k) { return reference.uvs[size_t(reference.faceIndices[size_t(3 * triangle + k)])]; };
        return (1.0f - u - v) * at(0) + u * at(1) + v * at(2);
    };
    std::vector<glm::vec2> corners(4 * size_t(faces), glm::vec2(0.5f));
    std::vector<char> found(size_t(faces), 0);
    for (int f = 0; f < faces; ++f) {
        std::array<std::optional<Hit>, kGrid * kGrid> hits;
        for (int k = 0; k < kGrid * kGrid; ++k) {
            const auto& hit = casts.hits[size_t(f) * kGrid * kGrid + size_t(k)];
            if (!hit) continue;
            const size_t base = size_t(3 * hit->triangle);
            const glm::vec3 p0 = reference.positions[size_t(reference.faceIndices[base])],
                            p1 = reference.positions[size_t(reference.faceIndices[base + 1])],
                            p2 = reference.positions[size_t(reference.faceIndices[base + 2])];
            const glm::vec2 t0 = texcoord(hit->triangle, 0, 0), t1 = texcoord(hit->triangle, 1, 0),
                            t2 = texcoord(hit->triangle, 0, 1);
            const float area = glm::length(glm::cross(p1 - p0, p2 - p0));
            const float uvArea = std::abs((t1.x - t0.x) * (t2.y - t0.y) - (t2.x - t0.x) * (t1.y - t0.y));
            const glm::vec3 point = origins[size_t(f) * kGrid * kGrid + size_t(k)] +
                                    hit->distance * normals[size_t(f) * kGrid * kGrid + size_t(k)];
            hits[size_t(k)] =
                Hit{point, texcoord(hit->triangle, hit->u, hit->v), area > 0.0f ? std::sqrt(uvArea / area) : 0.0f};
        }
        const std::vector<int> use = agreeingHits(hits);
        if (use.empty()) continue;
        const auto fitted = fitCorners(hits, use);
        std::copy(fitted.begin(), fitted.end(), corners.begin() + 4 * std::ptrdiff_t(f));
        found[size_t(f)] = 1;
    }
    weldCorners(cage, corners, found);
    snapToVertexMeans(cage, corners);
    return corners;
}

}  // namespace subdfit::simplify
