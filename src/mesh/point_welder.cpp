#include "mesh/point_welder.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace subdfit::mesh {
namespace {

long long cellKey(long long x, long long y, long long z) { return (x * 73856093LL) ^ (y * 19349663LL) ^ (z * 83492791LL); }

}  // namespace

int PointWelder::indexOf(const glm::vec3& p, int& nextIndex) {
    const long long cx = std::llround(p.x / cell_), cy = std::llround(p.y / cell_), cz = std::llround(p.z / cell_);
    for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
            for (long long dz = -1; dz <= 1; ++dz) {
                const auto it = cells_.find(cellKey(cx + dx, cy + dy, cz + dz));
                if (it == cells_.end()) continue;
                for (const auto& [q, index] : it->second)
                    if (glm::length(p - q) <= cell_) return index;
            }
    cells_[cellKey(cx, cy, cz)].push_back({p, nextIndex});
    return nextIndex++;
}

std::vector<glm::vec3> coincidentPointsMerged(const std::vector<glm::vec3>& points) {
    float extent = 0.0f;
    for (const glm::vec3& p : points) extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    PointWelder welder(std::max(extent, 1e-30f) * 1e-6f);
    std::vector<glm::vec3> merged(points.size()), first;
    int next = 0;
    for (size_t v = 0; v < points.size(); ++v) {
        const int index = welder.indexOf(points[v], next);
        if (index == int(first.size())) first.push_back(points[v]);
        merged[v] = first[size_t(index)];
    }
    return merged;
}

}  // namespace subdfit::mesh
