// Hard edges of a reference become creases and corners of its cage (simplify/cage/feature_edges.h):
// a flat-shaded box's edges, not the coarse cage's turns over a smooth sphere.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"
#include "simplify/cage/decimate.h"
#include "simplify/cage/feature_edges.h"
#include "simplify/cage/initial_cage.h"
#include "split_triangles.h"
#include "subdiv/limit_evaluator.h"

namespace subdfit::simplify {
namespace {

// A quad sphere pushed out onto the cube [−1, 1]³: 6 n² quads, flat sides.
mesh::PolygonMesh cubeGrid(int n) {
    mesh::PolygonMesh cube = mesh::makeQuadSphere(n);
    for (glm::vec3& p : cube.positions) p /= std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return cube;
}

// The reference's vertex nearest to `p`, exactly as the reference has it.
glm::vec3 vertexNear(const mesh::PolygonMesh& reference, const glm::vec3& p) {
    return *std::min_element(
        reference.positions.begin(), reference.positions.end(),
        [&](const glm::vec3& a, const glm::vec3& b) { return glm::distance(a, p) < glm::distance(b, p); });
}

// The 12 triangles of a cube whose corners are the reference's vertices nearest (±1, ±1, ±1).
mesh::PolygonMesh boxCage(const mesh::PolygonMesh& reference) {
    mesh::PolygonMesh cage;
    for (int k = 0; k < 8; ++k)
        cage.positions.push_back(
            vertexNear(reference, {k & 1 ? 1.0f : -1.0f, k & 2 ? 1.0f : -1.0f, k & 4 ? 1.0f : -1.0f}));
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        cage.faceIndices.insert(cage.faceIndices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        cage.faceSizes.insert(cage.faceSizes.end(), {3, 3});
    }
    return cage;
}

TEST(FeatureEdges, AFlatShadedBoxCreasesItsTwelveEdgesAndNotItsDiagonals) {
    const mesh::PolygonMesh reference = testing::splitTriangles(cubeGrid(4));
    mesh::PolygonMesh cage = boxCage(reference);
    const FeatureCount found = tagFeatures(cage, reference);
    EXPECT_EQ(found.creases, 12);
    EXPECT_EQ(found.corners, 0);
    ASSERT_EQ(cage.tags.creases.size(), 12u);
    for (const mesh::Crease& crease : cage.tags.creases) {
        // A cube edge joins corners that differ in one coordinate; a diagonal in two.
        const glm::vec3 d = glm::abs(cage.positions[size_t(crease.v0)] - cage.positions[size_t(crease.v1)]);
        EXPECT_EQ(int(d.x > 1.0f) + int(d.y > 1.0f) + int(d.z > 1.0f), 1);
        EXPECT_EQ(crease.sharpness, 10.0f);
    }
}

TEST(FeatureEdges, ACoarseCageOverASmoothSphereGetsNoCreases) {
    // The same eight-corner cage turns by 90° at its edges, but the sphere under it is smooth:
    // welded (shaded smooth) or flat-shaded with faces a few degrees apart.
    const mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(8));
    for (const mesh::PolygonMesh& reference : {sphere, testing::splitTriangles(sphere)}) {
        mesh::PolygonMesh cage = boxCage(reference);
        const FeatureCount found = tagFeatures(cage, reference);
        EXPECT_EQ(found.creases, 0);
        EXPECT_EQ(found.corners, 0);
        EXPECT_TRUE(cage.tags.creases.empty());
    }
}

TEST(FeatureEdges, ASquarePlateKeepsItsFourCorners) {
    const mesh::PolygonMesh plate = mesh::triangulated(mesh::makeQuadGrid(6));
    mesh::PolygonMesh cage;
    for (const glm::vec3 corner : {glm::vec3(-1, -1, 0), glm::vec3(1, -1, 0), glm::vec3(1, 1, 0), glm::vec3(-1, 1, 0)})
        cage.positions.push_back(vertexNear(plate, corner));
    cage.positions.push_back(vertexNear(plate, {0, -1, 0}));  // on a straight stretch of the rim
    cage.faceIndices = {0, 4, 2, 4, 1, 2, 0, 2, 3};
    cage.faceSizes = {3, 3, 3};
    const FeatureCount found = tagFeatures(cage, plate);
    EXPECT_EQ(found.corners, 4);
    EXPECT_EQ(found.creases, 0);
    std::set<int> corners;
    for (const mesh::Corner& c : cage.tags.corners) corners.insert(c.vertex);
    EXPECT_EQ(corners, (std::set<int>{0, 1, 2, 3}));
}

TEST(FeatureEdges, TheInitialCageOfABoxIsABoxNotAPillow) {
    // Without the creases the limit surface of a box cage rounds every edge inwards by a good
    // fraction of the box; with them the cage's limit stays on the box.
    const mesh::PolygonMesh reference = testing::splitTriangles(cubeGrid(6));
    auto worstDistance = [&](bool hardEdges) {
        const mesh::PolygonMesh cage = initialCage(reference, {.faces = 12, .hardEdges = hardEdges});
        const subdiv::LimitEvaluator limit(cage);
        float worst = 0.0f;
        for (int face = 0; face < limit.ptexFaceCount(); ++face)
            for (float u : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f})
                for (float v : {0.0f, 0.25f, 0.5f, 0.75f, 1.0f}) {
                    if (!limit.hasSurface(face, u, v)) continue;
                    const glm::vec3 p = limit.evaluate(face, u, v, cage.positions).position;
                    worst = std::max(worst, std::abs(1.0f - std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)})));
                }
        return worst;
    };
    const float rounded = worstDistance(false), creased = worstDistance(true);
    EXPECT_GT(rounded, 0.1f);
    EXPECT_LT(creased, 0.01f);
}

}  // namespace
}  // namespace subdfit::simplify
