#include "surface/texel_layout.h"

#include <glm/geometric.hpp>
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "mesh/point_welder.h"
#include "subdiv/limit_evaluator.h"
#include "util/error.h"

namespace subdfit::surface {


TexelLayout buildTexelLayout(const mesh::PolygonMesh& cage, int resolution) {
    SUBDFIT_CHECK(resolution >= 1 && resolution <= 256);
    const subdiv::LimitEvaluator evaluator(cage);
    TexelLayout layout;
    layout.resolution = resolution;
    layout.ptexFaceCount = evaluator.ptexFaceCount();
    layout.faceNodes.resize(size_t(layout.ptexFaceCount) * size_t(layout.nodesPerFace()));

    float extent = 0.0f;
    for (const auto& p : cage.positions) extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    // Far below the node spacing of any sane map, far above float rounding of one limit point.
    mesh::PointWelder welder(std::max(extent, 1e-30f) * 1e-5f);
    int next = 0;
    const int n = resolution;
    for (int face = 0; face < layout.ptexFaceCount; ++face) {
        const bool surface = evaluator.hasSurface(face, 0.5f, 0.5f);
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const bool border = i == 0 || j == 0 || i == n || j == n;
                int index;
                if (border && surface) {
                    const auto p = evaluator.evaluate(face, float(i) / float(n), float(j) / float(n), cage.positions).position;
                    index = welder.indexOf(p, next);
                } else {
                    index = next++;  // interior nodes (and holes) are their tile's own
                }
                layout.faceNodes[size_t(face) * size_t(layout.nodesPerFace()) + size_t(j) * size_t(n + 1) + size_t(i)] = index;
            }
    }
    layout.nodeCount = next;
    return layout;
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
    auto value = [&](int a, int b) { return values[size_t(layout.node(face, a, b)) * size_t(stride) + size_t(channel)]; };
    return (1 - fx) * (1 - fy) * value(i, j) + fx * (1 - fy) * value(i + 1, j) + (1 - fx) * fy * value(i, j + 1) +
           fx * fy * value(i + 1, j + 1);
}

}  // namespace subdfit::surface
