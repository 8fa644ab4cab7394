#include "mesh/point_welder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

namespace subdfit::mesh {
namespace {

// SplitMix64's finaliser: every input bit reaches every output bit.
std::uint64_t mixed(std::uint64_t x) {
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
}

}  // namespace

PointWelder::Slot* PointWelder::find(const Cell& cell) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t at =
        std::size_t(mixed(mixed(mixed(std::uint64_t(cell[0])) ^ std::uint64_t(cell[1])) ^ std::uint64_t(cell[2])));
    for (;; at = (at + 1) & mask) {  // linear probing
        Slot& slot = slots_[at & mask];
        if (slot.head < 0 || slot.cell == cell) return &slot;
    }
}

void PointWelder::grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(old.empty() ? 1024 : old.size() * 2, Slot{});
    for (const Slot& slot : old)
        if (slot.head >= 0) *find(slot.cell) = slot;
}

int PointWelder::indexOf(const glm::vec3& p, int& nextIndex) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    // Cells twice the tolerance: a point within it lies in p's cell or, along each axis, in the
    // one neighbour on the side of the cell's centre p is on.
    const glm::vec3 at = p / (2.0f * tolerance_);
    const Cell cell{std::int64_t(std::floor(at.x)), std::int64_t(std::floor(at.y)), std::int64_t(std::floor(at.z))};
    const Cell side{at.x - float(cell[0]) < 0.5f ? -1 : 1, at.y - float(cell[1]) < 0.5f ? -1 : 1,
                    at.z - float(cell[2]) < 0.5f ? -1 : 1};
    for (int k = 0; k < 8; ++k) {
        const Slot* slot = find(
            Cell{cell[0] + (k & 1 ? side[0] : 0), cell[1] + (k & 2 ? side[1] : 0), cell[2] + (k & 4 ? side[2] : 0)});
        for (int i = slot->head; i >= 0; i = points_[std::size_t(i)].next)
            if (glm::length(p - points_[std::size_t(i)].position) <= tolerance_) return points_[std::size_t(i)].index;
    }
    Slot* slot = find(cell);
    const int added = int(points_.size());
    points_.push_back({p, nextIndex, -1});
    if (slot->head < 0) {
        *slot = {.cell = cell, .head = added, .tail = added};
        ++used_;
    } else {
        points_[std::size_t(slot->tail)].next = added;
        slot->tail = added;
    }
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
