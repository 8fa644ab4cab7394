#include "geometry/surface_distance.h"
#include "geometry/surface_queries.h"
#include "util/interrupt.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <random>

namespace subdfit::geometry {
namespace {

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

// Distances from each sample to the nearest point of `target`.
std::vector<double> distancesTo(const std::vector<glm::vec3>& samples, const SurfaceQueries& target) {
    std::vector<double> out;
    out.reserve(samples.size());
    for (const auto& p : samples) {
        if (out.size() % 4096 == 0) throwIfStopRequested();
        out.push_back(double(target.closestDistance(p)));
    }
    return out;
}

}  // namespace

SurfaceDistance surfaceDistance(const mesh::PolygonMesh& a, const SurfaceQueries& b, int samples, std::uint32_t seed) {
    SurfaceDistance result;
    double sumDistance = 0.0;
    size_t count = 0;
    for (const auto& d : {distancesTo(sampleSurface(a, samples, seed), b),
                          distancesTo(sampleSurface(b.mesh(), samples, seed + 1), SurfaceQueries(a))}) {
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

SurfaceDistance surfaceDistance(const mesh::PolygonMesh& a, const mesh::PolygonMesh& b, int samples,
                                std::uint32_t seed) {
    return surfaceDistance(a, SurfaceQueries(b), samples, seed);
}

}  // namespace subdfit::geometry
