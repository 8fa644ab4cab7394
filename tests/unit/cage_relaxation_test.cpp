// Where the relaxation pulls each cage vertex: the start cage's own layout, low-passed, so that
// a graded layout survives and vertex noise does not.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fit/cage_relaxation.h"
#include "mesh/procedural.h"

namespace subdfit::fit {
namespace {

// A 16 × 16 grid whose columns crowd towards x = −1 (spacing growing linearly): the kind of
// layout an artist gives a cage near a feature.
mesh::PolygonMesh gradedGrid() {
    mesh::PolygonMesh grid = mesh::makeQuadGrid(16);
    for (auto& p : grid.positions) p.x = 0.5f * (p.x + 1.0f) * (p.x + 1.0f) - 1.0f;
    return grid;
}

double rmsDifference(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b, const RelaxationTopology& t) {
    double sum = 0.0;
    int n = 0;
    for (size_t v = 0; v < a.size(); ++v)
        if (t.modes[v] == RelaxationTopology::Surface) {
            sum += double(glm::dot(a[v] - b[v], a[v] - b[v]));
            ++n;
        }
    return std::sqrt(sum / std::max(1, n));
}

TEST(CageRelaxation, WithoutLowPassTheStartCageIsWhereItRelaxesTo) {
    const auto grid = gradedGrid();
    const auto topology = relaxationTopology(grid);
    const auto offsets = restOffsets(grid, topology, 0);
    for (size_t v = 0; v < grid.positions.size(); ++v) {
        const int begin = topology.offsets[v], end = topology.offsets[v + 1];
        if (end == begin) continue;
        glm::vec3 centroid(0.0f);
        for (int k = begin; k < end; ++k) centroid += grid.positions[size_t(topology.neighbors[size_t(k)])];
        centroid /= float(end - begin);
        EXPECT_LT(glm::length(centroid + offsets[v] - grid.positions[v]), 1e-6f) << "vertex " << v;
    }
}

TEST(CageRelaxation, TheLowPassKeepsAGradedLayoutAndDropsVertexNoise) {
    const auto grid = gradedGrid();
    const auto topology = relaxationTopology(grid);
    const auto clean = restOffsets(grid, topology, 0);
    // The layout's own offsets change slowly from vertex to vertex: the low pass keeps most.
    const double cleanScale = rmsDifference(clean, std::vector<glm::vec3>(clean.size(), glm::vec3(0.0f)), topology);
    EXPECT_GT(cleanScale, 1e-3);
    EXPECT_LT(rmsDifference(restOffsets(grid, topology, CageRelaxation::kRestPasses), clean, topology),
              0.5 * cleanScale);

    auto noised = grid;
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 0.01f);
    for (auto& p : noised.positions) p += glm::vec3(noise(rng), noise(rng), 0.0f);
    const double raw = rmsDifference(restOffsets(noised, topology, 0), clean, topology);
    const double filtered = rmsDifference(restOffsets(noised, topology, CageRelaxation::kRestPasses), clean, topology);
    std::printf("offset error from noise: %.4f unfiltered, %.4f low-passed (layout's own scale %.4f)\n", raw, filtered,
                cleanScale);
    EXPECT_LT(filtered, 0.5 * raw);
}

}  // namespace
}  // namespace subdfit::fit
