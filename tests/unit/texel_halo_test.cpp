// The ring of nodes across each tile's edges (TexelLayout::halo) and what it is for: slopes of
// the displacement, and so the displaced surface's shading normals, that agree on both sides of
// a face edge instead of kinking at every edge of the cage.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "mesh/procedural.h"
#include "subdiv/limit_evaluator.h"
#include "surface/displaced_surface.h"

namespace subdfit::test {
namespace {

surface::SurfaceMaps displacedBy(const mesh::PolygonMesh& cage, int resolution, float amplitude, std::uint32_t seed) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, resolution);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> height(-amplitude, amplitude);
    maps.displacement.resize(size_t(maps.layout.nodeCount));
    for (float& d : maps.displacement) d = height(rng);
    return maps;
}

// Where each node sits on the limit surface (a node's tiles all agree: they are welded so).
std::vector<glm::vec3> nodePositions(const mesh::PolygonMesh& cage, const surface::TexelLayout& layout) {
    const subdiv::LimitEvaluator limit(cage);
    const int n = layout.resolution;
    std::vector<glm::vec3> at(size_t(layout.nodeCount));
    for (int f = 0; f < layout.ptexFaceCount; ++f)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i)
                at[size_t(layout.node(f, i, j))] =
                    limit.evaluate(f, float(i) / float(n), float(j) / float(n), cage.positions).position;
    return at;
}

TEST(TexelHalo, EachEdgeSeesTheNeighbouringTileOneRowIn) {
    const auto cage = mesh::makeQuadSphere(3);
    const auto layout = surface::buildTexelLayout(cage, 3);
    const int n = layout.resolution;
    const auto position = nodePositions(cage, layout);
    const float cell = glm::length(position[size_t(layout.node(0, 1, 1))] - position[size_t(layout.node(0, 2, 1))]);
    ASSERT_EQ(layout.halo.size(), size_t(layout.ptexFaceCount) * 4 * size_t(n + 1));
    for (int f = 0; f < layout.ptexFaceCount; ++f)
        for (int edge = 0; edge < 4; ++edge)
            for (int k = 1; k < n; ++k) {  // the corners' rings are checked through the slopes below
                const int across = layout.halo[(size_t(f) * 4 + size_t(edge)) * size_t(n + 1) + size_t(k)];
                ASSERT_GE(across, 0) << "a closed cage has a tile across every edge";
                const glm::ivec2 border = edge == 0   ? glm::ivec2(k, 0)
                                          : edge == 1 ? glm::ivec2(n, k)
                                          : edge == 2 ? glm::ivec2(k, n)
                                                      : glm::ivec2(0, k);
                const glm::ivec2 inner = edge == 0   ? glm::ivec2(k, 1)
                                         : edge == 1 ? glm::ivec2(n - 1, k)
                                         : edge == 2 ? glm::ivec2(k, n - 1)
                                                     : glm::ivec2(1, k);
                const glm::vec3 b = position[size_t(layout.node(f, border.x, border.y))];
                const glm::vec3 in = position[size_t(layout.node(f, inner.x, inner.y))];
                const glm::vec3 out = position[size_t(across)];
                // One cell beyond the border, on the far side from the tile's own row.
                EXPECT_NEAR(glm::length(out - b), cell, 0.5f * cell);
                EXPECT_LT(glm::dot(out - b, in - b), 0.0f);
            }
}

TEST(TexelHalo, WithoutANeighbourTheBorderSlopeIsExtended) {
    const auto grid = mesh::makeQuadGrid(3);  // open: its outer edges have no tile across
    surface::SurfaceMaps maps = displacedBy(grid, 4, 0.1f, 3);
    const auto& layout = maps.layout;
    int open = 0;
    for (int f = 0; f < layout.ptexFaceCount; ++f)
        for (int k = 0; k <= 4; ++k) {
            if (layout.halo[(size_t(f) * 4 + 0) * 5 + size_t(k)] >= 0) continue;
            ++open;
            const float extended = surface::nodeValueAcross(layout, maps.displacement, f, k, -1);
            const float border = maps.displacement[size_t(layout.node(f, k, 0))];
            const float inner = maps.displacement[size_t(layout.node(f, k, 1))];
            EXPECT_FLOAT_EQ(extended, 2.0f * border - inner);
        }
    EXPECT_EQ(open, 3 * 5);  // the grid's bottom row of faces, every position along its edge
}

// The angle between the shading normals two tiles give at the nodes they share (edge nodes, not
// the tile corners, where a cage vertex of any valence may sit).
struct Kink {
    double mean = 0.0, worst = 0.0;
};

template <class NormalAt>
Kink kinkAtSharedNodes(const surface::TexelLayout& layout, NormalAt normalAt) {
    const int n = layout.resolution;
    std::map<int, glm::vec3> first;
    Kink kink;
    int count = 0;
    for (int f = 0; f < layout.ptexFaceCount; ++f)
        for (int j = 0; j <= n; ++j)
            for (int i = 0; i <= n; ++i) {
                const bool border = i == 0 || j == 0 || i == n || j == n;
                const bool corner = (i == 0 || i == n) && (j == 0 || j == n);
                if (!border || corner) continue;
                const glm::vec3 normal = normalAt(f, float(i) / float(n), float(j) / float(n));
                const auto [it, isNew] = first.emplace(layout.node(f, i, j), normal);
                if (isNew) continue;
                const double angle = std::acos(std::clamp(double(glm::dot(it->second, normal)), -1.0, 1.0));
                kink.mean += angle, kink.worst = std::max(kink.worst, angle), ++count;
            }
    kink.mean /= std::max(count, 1);
    return kink;
}

TEST(TexelHalo, ShadingNormalsAgreeAcrossFaceEdges) {
    const auto cage = mesh::makeQuadSphere(4);
    const surface::SurfaceMaps maps = displacedBy(cage, 4, 0.01f, 7);  // ~1/4 of a cell: a rough bake
    const surface::DisplacedSurface surface(cage, maps);
    const Kink across =
        kinkAtSharedNodes(maps.layout, [&](int f, float u, float v) { return surface.at(f, u, v).normal; });

    // What one-sided differences at the tile's border (each tile on its own) gave.
    const subdiv::LimitEvaluator limit(cage);
    const float h = 0.5f / float(maps.layout.resolution);
    const Kink oneSided = kinkAtSharedNodes(maps.layout, [&](int f, float u, float v) {
        auto d = [&](float a, float b) {
            return surface::sampleBilinear(maps.layout, maps.displacement, 1, 0, f, a, b);
        };
        const float u0 = std::max(u - h, 0.0f), u1 = std::min(u + h, 1.0f), v0 = std::max(v - h, 0.0f),
                    v1 = std::min(v + h, 1.0f);
        const auto s = limit.evaluate(f, u, v, cage.positions);
        const glm::vec3 n = glm::normalize(glm::cross(s.dPdu, s.dPdv));
        const glm::vec3 du = s.dPdu + (d(u1, v) - d(u0, v)) / (u1 - u0) * n,
                        dv = s.dPdv + (d(u, v1) - d(u, v0)) / (v1 - v0) * n;
        return glm::normalize(glm::cross(du, dv));
    });
    std::printf(
        "shading kink at shared edge nodes: one-sided mean %.4f worst %.4f rad, across tiles mean %.5f worst %.5f\n",
        oneSided.mean, oneSided.worst, across.mean, across.worst);
    EXPECT_GT(oneSided.mean, 0.05);  // the random heights do kink the one-sided normals
    EXPECT_LT(across.mean, 0.02 * oneSided.mean);
    EXPECT_LT(across.worst, 0.1 * oneSided.worst);
}

}  // namespace
}  // namespace subdfit::test
