#include "geometry/surface_distance.h"

#include <glm/geometric.hpp>
#include <nanoflann.hpp>

#include <algorithm>
#include <random>

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

struct Centroids {
    std::vector<glm::vec3> points;
    size_t kdtree_get_point_count() const { return points.size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return points[i][int(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const { return false; }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Centroids>, Centroids, 3>;

glm::vec3 corner(const mesh::PolygonMesh& m, size_t tri, int k) { return m.positions[m.faceIndices[3 * tri + k]]; }

std::vector<glm::vec3> sampleSurface(const mesh::PolygonMesh& m, int count, std::uint32_t seed) {
    std::vector<double> cumulative;
    double total = 0.0;
    for (size_t t = 0; t < m.faceSizes.size(); ++t) {
        total += 0.5 * glm::length(glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0)));
        cumulative.push_back(total);
    }
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> pick(0.0, total);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<glm::vec3> samples;
    for (int i = 0; i < count && total > 0.0; ++i) {
        const size_t t = size_t(std::lower_bound(cumulative.begin(), cumulative.end(), pick(rng)) - cumulative.begin());
        float r1 = unit(rng), r2 = unit(rng);
        if (r1 + r2 > 1.0f) r1 = 1.0f - r1, r2 = 1.0f - r2;
        const size_t tri = std::min(t, m.faceSizes.size() - 1);
        samples.push_back(corner(m, tri, 0) + r1 * (corner(m, tri, 1) - corner(m, tri, 0)) +
                          r2 * (corner(m, tri, 2) - corner(m, tri, 0)));
    }
    return samples;
}

// Distances from each sample to the nearest triangle of `target`.
std::vector<double> distancesTo(const std::vector<glm::vec3>& samples, const mesh::PolygonMesh& target) {
    Centroids centroids;
    float longestEdge = 0.0f;
    for (size_t t = 0; t < target.faceSizes.size(); ++t) {
        centroids.points.push_back((corner(target, t, 0) + corner(target, t, 1) + corner(target, t, 2)) / 3.0f);
        for (int k = 0; k < 3; ++k)
            longestEdge = std::max(longestEdge, glm::length(corner(target, t, k) - corner(target, t, (k + 1) % 3)));
    }
    Tree tree(3, centroids, nanoflann::KDTreeSingleIndexAdaptorParams(16));
    tree.buildIndex();
    constexpr size_t candidates = 16;
    std::vector<double> out;
    out.reserve(samples.size());
    for (const auto& p : samples) {
        unsigned index[candidates];
        float squared[candidates];
        const size_t found = tree.knnSearch(&p.x, candidates, index, squared);
        float best = std::numeric_limits<float>::max();
        for (size_t k = 0; k < found; ++k)
            best = std::min(best, glm::length(p - closestOnTriangle(p, corner(target, index[k], 0),
                                                                    corner(target, index[k], 1),
                                                                    corner(target, index[k], 2))));
        out.push_back(double(best));
    }
    return out;
}

}  // namespace

SurfaceDistance surfaceDistance(const mesh::PolygonMesh& a, const mesh::PolygonMesh& b, int samples, std::uint32_t seed) {
    SurfaceDistance result;
    double sumDistance = 0.0;
    size_t count = 0;
    for (const auto& d : {distancesTo(sampleSurface(a, samples, seed), b),
                          distancesTo(sampleSurface(b, samples, seed + 1), a)}) {
        double sumSquared = 0.0;
        for (double x : d) {
            sumSquared += x * x;
            sumDistance += x;
            result.hausdorff = std::max(result.hausdorff, x);
        }
        result.chamferL2Squared += d.empty() ? 0.0 : sumSquared / double(d.size());
        count += d.size();
    }
    result.meanDistance = count ? sumDistance / double(count) : 0.0;
    return result;
}

}  // namespace subdfit::geometry
