#include "surface/texel_layout.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <list>
#include <mutex>
#include <unordered_map>

#include "mesh/point_welder.h"
#include "subdiv/limit_evaluator.h"
#include "util/error.h"
#include "util/parallel_for.h"

namespace subdfit::surface {
namespace {

// Node (i, j) of edge `edge`'s k-th position, and the step from that edge into the tile.
glm::ivec2 edgePosition(int edge, int k, int n) {
    switch (edge) {
        case 0: return {k, 0};
        case 1: return {n, k};
        case 2: return {k, n};
        default: return {0, k};
    }
}
// Bilinear blend of the cell whose lower corner is node (i, j), at (fx, fy) inside it.
template <class Value>
float blend(int i, int j, float fx, float fy, const Value& value) {
    return (1 - fx) * (1 - fy) * value(i, j) + fx * (1 - fy) * value(i + 1, j) + (1 - fx) * fy * value(i, j + 1) +
           fx * fy * value(i + 1, j + 1);
}

glm::ivec2 inward(int edge) {
    static constexpr std::array<glm::ivec2, 4> steps{glm::ivec2(0, 1), glm::ivec2(-1, 0), glm::ivec2(0, -1),
                                                     glm::ivec2(1, 0)};
    return steps[size_t(edge)];
}

// For every tile edge, the tile on the other side (the one other tile whose edge holds the same
// nodes, in either direction) and its nodes one row in.
std::vector<int> haloNodes(const TexelLayout& layout) {
    const int n = layout.resolution, faces = layout.ptexFaceCount;
    auto nodeAt = [&](int face, glm::ivec2 p) { return layout.node(face, p.x, p.y); };
    std::unordered_map<int, std::vector<std::pair<int, int>>> edgesAtEndpoint;  // node -> (face, edge)
    for (int face = 0; face < faces; ++face)
        for (int edge = 0; edge < 4; ++edge) {
            edgesAtEndpoint[nodeAt(face, edgePosition(edge, 0, n))].push_back({face, edge});
            edgesAtEndpoint[nodeAt(face, edgePosition(edge, n, n))].push_back({face, edge});
        }
    std::vector<int> halo(size_t(faces) * 4 * size_t(n + 1), -1);
    for (int face = 0; face < faces; ++face)
        for (int edge = 0; edge < 4; ++edge) {
            auto sameNodes = [&](int other, int otherEdge, bool reversed) {
                for (int k = 0; k <= n; ++k)
                    if (nodeAt(face, edgePosition(edge, k, n)) !=
                        nodeAt(other, edgePosition(otherEdge, reversed ? n - k : k, n)))
                        return false;
                return true;
            };
            if (nodeAt(face, edgePosition(edge, 0, n)) == nodeAt(face, edgePosition(edge, n, n)))
                continue;  // collapsed
            int matches = 0, across = -1, acrossEdge = -1;
            bool acrossReversed = false;
            for (const auto& [other, otherEdge] : edgesAtEndpoint[nodeAt(face, edgePosition(edge, 0, n))]) {
                if (other == face && otherEdge == edge) continue;
                for (bool reversed : {false, true})
                    if (sameNodes(other, otherEdge, reversed)) {
                        ++matches, across = other, acrossEdge = otherEdge, acrossReversed = reversed;
                        break;
                    }
            }
            if (matches != 1) continue;  // a boundary, or non-manifold: extend the slope instead
            for (int k = 0; k <= n; ++k)
                halo[(size_t(face) * 4 + size_t(edge)) * size_t(n + 1) + size_t(k)] =
                    nodeAt(across, edgePosition(acrossEdge, acrossReversed ? n - k : k, n) + inward(acrossEdge));
        }
    return halo;
}

}  // namespace

namespace {

// The cage's points about the centre of their bounds, and the largest distance from it: a layout
// depends on the shape alone, not on where it stands (far from the origin, the rounding of a
// limit point grows with the coordinates, not with the nodes' spacing).
std::pair<std::vector<glm::vec3>, float> centred(const std::vector<glm::vec3>& points) {
    glm::vec3 low(0.0f), high(0.0f);
    if (!points.empty()) low = high = points.front();
    for (const auto& p : points) low = glm::min(low, p), high = glm::max(high, p);
    const glm::vec3 centre = 0.5f * (low + high);
    std::vector<glm::vec3> out(points.size());
    float extent = 0.0f;
    for (size_t k = 0; k < points.size(); ++k) {
        out[k] = points[k] - centre;
        extent = std::max({extent, std::abs(out[k].x), std::abs(out[k].y), std::abs(out[k].z)});
    }
    return {std::move(out), extent};
}

TexelLayout layOut(const mesh::PolygonMesh& cage, int resolution) {
    const subdiv::LimitEvaluator evaluator(cage);
    const auto shape = centred(cage.positions);
    const std::vector<glm::vec3>& positions = shape.first;
    const float extent = shape.second;
    TexelLayout layout;
    layout.resolution = resolution;
    layout.ptexFaceCount = evaluator.ptexFaceCount();
    layout.faceNodes.resize(size_t(layout.ptexFaceCount) * size_t(layout.nodesPerFace()));

    // The limit points of the tile borders, evaluated on every core; welded in order below.
    const int n = resolution;
    const size_t perFace = size_t(layout.nodesPerFace());
    std::vector<char> surface(size_t(layout.ptexFaceCount));
    std::vector<glm::vec3> borderPoints(layout.faceNodes.size());
    const std::vector<glm::dvec3> points = evaluator.patchPoints(positions);
    parallelFor(0, layout.ptexFaceCount, [&](int face) {
        surface[size_t(face)] = evaluator.hasSurface(face, 0.5f, 0.5f);
        if (!surface[size_t(face)]) return;
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i)
                if (i == 0 || j == 0 || i == n || j == n)
                    borderPoints[size_t(face) * perFace + size_t(j) * size_t(n + 1) + size_t(i)] =
                        evaluator.evaluate(face, float(i) / float(n), float(j) / float(n), points).position;
    });

    // Far below the node spacing of any sane map, far above float rounding of one limit point.
    mesh::PointWelder welder(std::max(extent, 1e-30f) * 1e-5f);
    int next = 0;
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const bool border = i == 0 || j == 0 || i == n || j == n;
                const size_t at = size_t(face) * perFace + size_t(j) * size_t(n + 1) + size_t(i);
                // Interior nodes (and holes) are their tile's own.
                layout.faceNodes[at] =
                    border && surface[size_t(face)] ? welder.indexOf(borderPoints[at], next) : next++;
            }
    layout.nodeCount = next;
    layout.halo = haloNodes(layout);
    return layout;
}

// What a layout depends on: the nodes on tile borders are welded where their limit points meet.
struct LayoutKey {
    int resolution = 0;
    std::vector<glm::vec3> positions;
    std::vector<int> faceSizes, faceIndices;
    mesh::SubdivisionTags tags;
    friend bool operator==(const LayoutKey&, const LayoutKey&) = default;
};

// The layouts of the last few cages, at most kMostNodes node slots in all (the newest always
// kept). simplify lays one (decoded) cage out again for every candidate it encodes, decodes and
// draws with maps; on a dense cage each costs tens of ms.
class LayoutCache {
public:
    TexelLayout get(const mesh::PolygonMesh& cage, int resolution) {
        LayoutKey key{resolution, cage.positions, cage.faceSizes, cage.faceIndices, cage.tags};
        {
            const std::lock_guard lock(mutex_);
            for (auto it = entries_.begin(); it != entries_.end(); ++it)
                if (it->first == key) {
                    entries_.splice(entries_.begin(), entries_, it);
                    return it->second;
                }
        }
        TexelLayout layout = layOut(cage, resolution);  // unlocked: another thread's cage need not wait
        const std::lock_guard lock(mutex_);
        entries_.emplace_front(std::move(key), layout);
        size_t slots = 0;
        for (const auto& entry : entries_) slots += entry.second.faceNodes.size();
        while (entries_.size() > 1 && (entries_.size() > kKept || slots > kMostNodes)) {
            slots -= entries_.back().second.faceNodes.size();
            entries_.pop_back();
        }
        return layout;
    }

private:
    static constexpr size_t kKept = 8;
    static constexpr size_t kMostNodes = size_t(16) << 20;  // 64 MB of node indices, and the halos
    std::mutex mutex_;
    std::list<std::pair<LayoutKey, TexelLayout>> entries_;
};

}  // namespace

TexelLayout buildTexelLayout(const mesh::PolygonMesh& cage, int resolution) {
    SUBDFIT_CHECK(resolution >= 1 && resolution <= 256);
    static LayoutCache cache;
    return cache.get(cage, resolution);
}

NodeAdjacency nodeAdjacency(const TexelLayout& layout) {
    std::vector<std::vector<int>> neighbours(size_t(layout.nodeCount));
    const int n = layout.resolution;
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const int a = layout.node(face, i, j);
                if (i < n) {
                    const int b = layout.node(face, i + 1, j);
                    neighbours[size_t(a)].push_back(b);
                    neighbours[size_t(b)].push_back(a);
                }
                if (j < n) {
                    const int b = layout.node(face, i, j + 1);
                    neighbours[size_t(a)].push_back(b);
                    neighbours[size_t(b)].push_back(a);
                }
            }
    NodeAdjacency adjacency;
    adjacency.offsets.push_back(0);
    for (int a = 0; a < layout.nodeCount; ++a) {
        auto& list = neighbours[size_t(a)];
        std::sort(list.begin(), list.end());
        list.erase(std::unique(list.begin(), list.end()), list.end());
        list.erase(std::remove(list.begin(), list.end(), a), list.end());  // welded degenerate edges
        adjacency.neighbors.insert(adjacency.neighbors.end(), list.begin(), list.end());
        adjacency.offsets.push_back(int(adjacency.neighbors.size()));
    }
    return adjacency;
}

float sampleBilinear(const TexelLayout& layout, std::span<const float> values, int stride, int channel, int face,
                     float u, float v) {
    const int n = layout.resolution;
    const float x = std::clamp(u, 0.0f, 1.0f) * float(n), y = std::clamp(v, 0.0f, 1.0f) * float(n);
    const int i = std::min(int(x), n - 1), j = std::min(int(y), n - 1);
    const float fx = x - float(i), fy = y - float(j);
    return blend(i, j, fx, fy, [&](int a, int b) {
        return values[size_t(layout.node(face, a, b)) * size_t(stride) + size_t(channel)];
    });
}

float nodeValueAcross(const TexelLayout& layout, std::span<const float> values, int face, int i, int j) {
    const int n = layout.resolution;
    const int edge = j < 0 ? 0 : i > n ? 1 : j > n ? 2 : i < 0 ? 3 : -1;
    if (edge < 0) return values[size_t(layout.node(face, i, j))];
    const int k = edge == 0 || edge == 2 ? i : j;
    if (const int across = layout.halo[(size_t(face) * 4 + size_t(edge)) * size_t(n + 1) + size_t(k)]; across >= 0)
        return values[size_t(across)];
    const glm::ivec2 border = glm::clamp(glm::ivec2(i, j), glm::ivec2(0), glm::ivec2(n)),
                     inner = 2 * border - glm::ivec2(i, j);
    return 2.0f * values[size_t(layout.node(face, border.x, border.y))] -
           values[size_t(layout.node(face, inner.x, inner.y))];
}

namespace {

// Bilinear at (u, v) with at most one of them up to a cell outside [0, 1]: the cell there spans
// the tile's border nodes and the ring across it.
float sampleAcross(const TexelLayout& layout, std::span<const float> values, int face, float u, float v) {
    const int n = layout.resolution;
    auto cellOf = [n](float x) { return x < 0.0f ? -1 : x >= float(n) ? n : std::min(int(x), n - 1); };
    const float x = std::clamp(u * float(n), -1.0f, float(n + 1)), y = std::clamp(v * float(n), -1.0f, float(n + 1));
    const int i = cellOf(x), j = cellOf(y);
    const float fx = x - float(i), fy = y - float(j);
    return blend(i, j, fx, fy, [&](int a, int b) { return nodeValueAcross(layout, values, face, a, b); });
}

}  // namespace

glm::vec2 slopeAcrossTiles(const TexelLayout& layout, std::span<const float> values, int face, float u, float v) {
    const float h = 0.5f / float(layout.resolution);
    u = std::clamp(u, 0.0f, 1.0f), v = std::clamp(v, 0.0f, 1.0f);
    return {(sampleAcross(layout, values, face, u + h, v) - sampleAcross(layout, values, face, u - h, v)) / (2.0f * h),
            (sampleAcross(layout, values, face, u, v + h) - sampleAcross(layout, values, face, u, v - h)) / (2.0f * h)};
}

}  // namespace subdfit::surface
