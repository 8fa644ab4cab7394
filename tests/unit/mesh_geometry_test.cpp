// Triangulation, vertex normals and adjacency, including degenerate input.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/mesh_adjacency.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"

namespace subdfit::mesh {
namespace {

PolygonMesh unitCube() {
    PolygonMesh cube;
    cube.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    cube.faceSizes = {4, 4, 4, 4, 4, 4};
    cube.faceIndices = {0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7};
    return cube;
}

void expectFiniteUnit(const std::vector<glm::vec3>& normals) {
    for (size_t i = 0; i < normals.size(); ++i) {
        EXPECT_TRUE(std::isfinite(normals[i].x) && std::isfinite(normals[i].y) && std::isfinite(normals[i].z)) << i;
        EXPECT_NEAR(glm::length(normals[i]), 1.0f, 1e-5f) << i;
    }
}

TEST(MeshGeometry, TriangulatesFansAndLeavesOutHoles) {
    PolygonMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {1, 2, 0}, {0, 1, 0}, {5, 5, 5}};
    mesh.faceSizes = {5, 3, 3};
    mesh.faceIndices = {0, 1, 2, 3, 4, 0, 1, 5, 1, 2, 5};
    mesh.tags.holes = {2};
    mesh.tags.creases = {{0, 1, 2.0f}};
    const PolygonMesh tris = triangulated(mesh);
    EXPECT_EQ(tris.faceSizes, std::vector<int>(4, 3));
    EXPECT_EQ(tris.faceIndices, (std::vector<int>{0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 1, 5}));
    EXPECT_EQ(tris.positions, mesh.positions);
    EXPECT_TRUE(tris.tags.creases.empty());
}

TEST(MeshGeometry, CubeNormalsPointOutwards) {
    const PolygonMesh cube = unitCube();
    const auto normals = vertexNormals(cube);
    ASSERT_EQ(normals.size(), 8u);
    expectFiniteUnit(normals);
    for (size_t i = 0; i < 8; ++i) {
        const glm::vec3 outwards = glm::normalize(cube.positions[i] - glm::vec3(0.5f));
        EXPECT_NEAR(glm::dot(normals[i], outwards), 1.0f, 1e-5f) << i;
    }
}

TEST(MeshGeometry, DegenerateMeshesGiveFiniteOutput) {
    PolygonMesh mesh;
    mesh.positions = {
        {0, 0, 0},      {0, 0, 0},      {0, 0, 0},       // a point-sized triangle
        {0, 0, 0},      {1, 0, 0},      {2, 0, 0},       // a collinear one
        {1e-30f, 0, 0}, {0, 1e-30f, 0}, {0, 0, 0},       // tiny but not zero
        {3e38f, 0, 0},  {0, 3e38f, 0},  {-3e38f, 0, 0},  // huge
        {7, 7, 7},                                       // used by no face
    };
    mesh.faceSizes = {3, 3, 3, 3, 4};
    mesh.faceIndices = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 3, 4, 4, 3};
    const auto normals = vertexNormals(mesh);
    ASSERT_EQ(normals.size(), mesh.positions.size());
    expectFiniteUnit(normals);
    EXPECT_NEAR(normals[6].z, 1.0f, 1e-5f);  // the tiny triangle still has a direction
    EXPECT_EQ(normals[12], glm::vec3(0, 0, 1));

    const PolygonMesh tris = triangulated(mesh);
    EXPECT_EQ(tris.faceCount(), 6);
    expectFiniteUnit(vertexNormals(tris));
}

// A glTF without normals as viewers draw it: each triangle flat, its corners' other attributes kept.
TEST(MeshGeometry, FlatShadedGivesEveryTriangleItsOwnVerticesAndFaceNormal) {
    PolygonMesh cube = triangulated(unitCube());
    cube.uvs.resize(cube.positions.size());
    for (size_t v = 0; v < cube.uvs.size(); ++v) cube.uvs[v] = glm::vec2(float(v), 0.5f);
    cube.positions.push_back({2, 2, 2});  // a degenerate triangle: no area, still a unit normal
    cube.uvs.push_back({9, 9});
    cube.faceSizes.push_back(3);
    cube.faceIndices.insert(cube.faceIndices.end(), {8, 8, 8});
    const PolygonMesh flat = flatShaded(cube);
    ASSERT_EQ(flat.faceCount(), cube.faceCount());
    ASSERT_EQ(flat.vertexCount(), 3 * cube.faceCount());
    ASSERT_EQ(flat.normals.size(), flat.positions.size());
    ASSERT_EQ(flat.uvs.size(), flat.positions.size());
    expectFiniteUnit(flat.normals);
    for (int f = 0; f < flat.faceCount(); ++f) {
        const int* v = &flat.faceIndices[3 * size_t(f)];
        const int* source = &cube.faceIndices[3 * size_t(f)];
        for (int k = 0; k < 3; ++k) {
            EXPECT_EQ(flat.positions[size_t(v[k])], cube.positions[size_t(source[k])]);
            EXPECT_EQ(flat.uvs[size_t(v[k])], cube.uvs[size_t(source[k])]);
            EXPECT_EQ(flat.normals[size_t(v[k])], flat.normals[size_t(v[0])]);  // one normal a face
        }
    }
    // A cube's face normal is an axis, pointing out: the first face (z = 0) looks down.
    EXPECT_EQ(flat.normals[size_t(flat.faceIndices[0])], glm::vec3(0, 0, -1));
}

TEST(MeshGeometry, AdjacencyHasUniqueSortedEdgeNeighbours) {
    PolygonMesh mesh;
    mesh.positions.resize(6);
    // Two quads sharing edge 1-4, and a degenerate triangle with a repeated vertex.
    mesh.faceSizes = {4, 4, 3};
    mesh.faceIndices = {0, 1, 4, 3, 1, 2, 5, 4, 2, 2, 5};
    const VertexAdjacency adjacency = vertexAdjacency(mesh);
    ASSERT_EQ(adjacency.offsets.size(), 7u);
    auto neighbours = [&](int v) {
        return std::vector<int>(adjacency.neighbors.begin() + adjacency.offsets[size_t(v)],
                                adjacency.neighbors.begin() + adjacency.offsets[size_t(v) + 1]);
    };
    EXPECT_EQ(neighbours(0), (std::vector<int>{1, 3}));
    EXPECT_EQ(neighbours(1), (std::vector<int>{0, 2, 4}));
    EXPECT_EQ(neighbours(2), (std::vector<int>{1, 5}));
    EXPECT_EQ(neighbours(4), (std::vector<int>{1, 3, 5}));
    EXPECT_EQ(adjacency.offsets.back(), int(adjacency.neighbors.size()));
}

TEST(MeshGeometry, ValidateMeshNamesTheSource) {
    PolygonMesh mesh = unitCube();
    mesh.sourcePath = "cage.obj";
    validateMesh(mesh);
    mesh.faceIndices[5] = 8;
    try {
        validateMesh(mesh);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "cage.obj: face index 8 is out of range (8 vertices)");
    }
    mesh = unitCube();
    mesh.sourcePath = "cage.obj";
    mesh.tags.holes = {6};
    EXPECT_THROW(validateMesh(mesh), Error);
}

}  // namespace
}  // namespace subdfit::mesh
