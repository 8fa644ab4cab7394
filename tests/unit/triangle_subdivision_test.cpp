// Midpoint subdivision keeps a textured asset's surface and appearance; the relief added to it
// keeps its texture seams closed and shaded alike on both sides.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <map>
#include <tuple>

#include "mesh/triangle_subdivision.h"
#include "surface/relief_surface.h"

namespace subdfit::mesh {
namespace {

// A unit square in z = 0 of two triangles whose texture is cut along the diagonal: the two
// triangles' charts are u = x, v = y and u = x + 1, v = y (vertices 0, 2 split into 4, 5).
PolygonMesh seamedSquare() {
    PolygonMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}, {1, 1, 0}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {1, 1}, {1, 0}, {2, 1}};
    m.faceSizes = {3, 3};
    m.faceIndices = {0, 1, 2, 4, 5, 3};
    m.faceMaterials = {0, 1};
    return m;
}

float area(const PolygonMesh& m) {
    float sum = 0.0f;
    for (int f = 0; f < m.faceCount(); ++f) {
        const int* t = &m.faceIndices[3 * size_t(f)];
        sum += 0.5f * glm::length(glm::cross(m.positions[size_t(t[1])] - m.positions[size_t(t[0])],
                                             m.positions[size_t(t[2])] - m.positions[size_t(t[0])]));
    }
    return sum;
}

TEST(TriangleSubdivision, FourTimesTheTrianglesOnTheSameSurfaceWithTheirCharts) {
    const PolygonMesh square = seamedSquare();
    const PolygonMesh split = subdividedTriangles(square, 2);
    ASSERT_EQ(split.faceCount(), 32);
    ASSERT_EQ(split.uvs.size(), split.positions.size());
    EXPECT_NEAR(area(split), 1.0f, 1e-6f);
    int second = 0;
    for (int f = 0; f < split.faceCount(); ++f) {
        const int material = split.faceMaterials[size_t(f)];
        second += material;
        for (int k = 0; k < 3; ++k) {  // each face's texture coordinates in its own chart
            const int v = split.faceIndices[3 * size_t(f) + size_t(k)];
            const glm::vec3 p = split.positions[size_t(v)];
            EXPECT_NEAR(split.uvs[size_t(v)].x, p.x + float(material), 1e-6f);
            EXPECT_NEAR(split.uvs[size_t(v)].y, p.y, 1e-6f);
        }
    }
    EXPECT_EQ(second, 16);
    // Along the diagonal, each chart has its own vertices: (0,0) .. (1,1) at 5 points, twice.
    EXPECT_EQ(split.vertexCount(), 15 + 15 - 5 + 5);
}

TEST(TriangleSubdivision, ReliefKeepsSeamsClosedAndShadedAlike) {
    PolygonMesh split = subdividedTriangles(seamedSquare(), 4);
    const PolygonMesh flat = split;
    surface::addRelief(split, {.amplitude = 0.01f, .shortestWavelength = 0.1f, .longestWavelength = 0.3f});
    std::map<std::tuple<float, float, float>, glm::vec3> moved, normals;
    ASSERT_EQ(split.normals.size(), split.positions.size());
    float largest = 0.0f;
    for (size_t v = 0; v < flat.positions.size(); ++v) {
        const glm::vec3 p = flat.positions[v];
        const auto [it, added] = moved.try_emplace({p.x, p.y, p.z}, split.positions[v]);
        if (!added) {
            EXPECT_EQ(it->second, split.positions[v]) << "a seam vertex moved apart at " << p.x << ", " << p.y;
        }
        const auto [normal, first] = normals.try_emplace({p.x, p.y, p.z}, split.normals[v]);
        if (!first) {
            EXPECT_EQ(normal->second, split.normals[v]) << "a seam vertex shades apart at " << p.x << ", " << p.y;
        }
        largest = std::max(largest, std::abs(split.positions[v].z));
        EXPECT_EQ(split.uvs[v], flat.uvs[v]);
    }
    EXPECT_GT(largest, 1e-3f);  // it did move
}

}  // namespace
}  // namespace subdfit::mesh
