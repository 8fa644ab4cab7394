// Triangles joined in pairs into quads (simplify/cage/triangle_pairing.h): a split quad mesh comes
// back as its quads, a decimated surface mostly quads; no join crosses a crease, a boundary, an
// edge of opposite windings or a hole's edge, and what comes out is the same surface, oriented.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "simplify/cage/decimate.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/cage/triangle_pairing.h"
#include "test_paths.h"

namespace subdfit::simplify {
namespace {

std::vector<std::vector<int>> facesOf(const mesh::PolygonMesh& m) {
    std::vector<std::vector<int>> faces;
    for (int f = 0, first = 0; f < m.faceCount(); first += m.faceSizes[size_t(f)], ++f)
        faces.emplace_back(m.faceIndices.begin() + first, m.faceIndices.begin() + first + m.faceSizes[size_t(f)]);
    return faces;
}

// Each face's corners from its smallest, in its winding: one key whatever corner it starts at.
std::vector<int> canonical(std::vector<int> face) {
    std::rotate(face.begin(), std::min_element(face.begin(), face.end()), face.end());
    return face;
}

double quadShare(const mesh::PolygonMesh& m) { return double(mesh::quadCount(m)) / double(m.faceCount()); }

// Every directed edge of `m` once at most (oriented), and the same edges as `triangles` but the
// joined diagonals: each pair's outline is its two triangles' outline.
void expectSameSurface(const mesh::PolygonMesh& triangles, const mesh::PolygonMesh& m) {
    std::multiset<std::pair<int, int>> before, after;
    for (const auto& f : facesOf(triangles))
        for (size_t k = 0; k < 3; ++k) before.insert({f[k], f[(k + 1) % 3]});
    for (const auto& f : facesOf(m))
        for (size_t k = 0; k < f.size(); ++k) after.insert({f[k], f[(k + 1) % f.size()]});
    const std::set<std::pair<int, int>> distinct(after.begin(), after.end());
    EXPECT_EQ(distinct.size(), after.size()) << "a directed edge used twice";
    int diagonals = 0;
    for (const auto& e : before)
        if (!after.contains(e)) {
            ++diagonals;
            EXPECT_TRUE(before.contains({e.second, e.first})) << "an outline edge lost";
        }
    for (const auto& e : after) EXPECT_TRUE(before.contains(e)) << "an edge made up";
    EXPECT_EQ(diagonals, 2 * mesh::quadCount(m));
    EXPECT_EQ(m.positions, triangles.positions);
}

TEST(TrianglePairing, ASplitQuadMeshComesBackAsItsQuads) {
    const mesh::PolygonMesh quads = mesh::makeQuadSphere(6);
    const mesh::PolygonMesh triangles = mesh::triangulated(quads);
    const mesh::PolygonMesh paired = pairTriangles(triangles);
    expectSameSurface(triangles, paired);
    std::set<std::vector<int>> want, got;
    for (const auto& f : facesOf(quads)) want.insert(canonical(f));
    for (const auto& f : facesOf(paired)) got.insert(canonical(f));
    EXPECT_EQ(got, want);
}

TEST(TrianglePairing, NoJoinAcrossACreaseABoundaryOrOppositeWindings) {
    // Two triangles of a unit square across the diagonal 0-2.
    mesh::PolygonMesh square;
    square.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    square.faceSizes = {3, 3};
    square.faceIndices = {0, 1, 2, 0, 2, 3};
    EXPECT_EQ(pairTriangles(square).faceSizes, std::vector<int>{4});

    mesh::PolygonMesh creased = square;
    creased.tags.creases = {{.v0 = 2, .v1 = 0, .sharpness = 10.0f}};
    EXPECT_EQ(pairTriangles(creased).faceSizes, (std::vector<int>{3, 3}));
    creased.tags.creases[0].sharpness = 0.0f;  // a crease of no sharpness is a smooth edge
    EXPECT_EQ(pairTriangles(creased).faceSizes, std::vector<int>{4});

    mesh::PolygonMesh flipped = square;
    flipped.faceIndices = {0, 1, 2, 0, 3, 2};  // both run 2 -> 0: wound opposite ways
    EXPECT_EQ(pairTriangles(flipped).faceSizes, (std::vector<int>{3, 3}));

    mesh::PolygonMesh holed = square;
    holed.tags.holes = {1};
    EXPECT_EQ(pairTriangles(holed).faceSizes, (std::vector<int>{3, 3}));
    EXPECT_EQ(pairTriangles(holed).tags.holes, std::vector<int>{1});
}

TEST(TrianglePairing, AFoldedOrPinchedPairStaysTwoTriangles) {
    mesh::PolygonMesh folded;  // the square folded 90 degrees along its diagonal
    folded.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5f, 0.5f, 0.7071f}};
    folded.faceSizes = {3, 3};
    folded.faceIndices = {0, 1, 2, 0, 2, 3};
    EXPECT_EQ(pairTriangles(folded).faceSizes, (std::vector<int>{3, 3}));
    mesh::PolygonMesh pinched = folded;  // flat, but the quad's corner at 3 is nearly straight
    pinched.positions[3] = {0.48f, 0.52f, 0.0f};
    EXPECT_EQ(pairTriangles(pinched).faceSizes, (std::vector<int>{3, 3}));
}

TEST(TrianglePairing, DecimatedShapesComeOutQuadDominant) {
    for (const char* name : {"catmark_bishop.obj", "catmark_pawn.obj", "catmark_torus_creases0.obj"}) {
        SCOPED_TRACE(name);
        const mesh::PolygonMesh shape = mesh::loadMesh(test::assetPath(std::string("osd-shapes/") + name));
        const mesh::PolygonMesh triangles = decimate(weldedTriangles(mesh::triangulated(shape)), 600);
        const mesh::PolygonMesh paired = pairTriangles(triangles);
        expectSameSurface(triangles, paired);
        EXPECT_GE(quadShare(paired), 0.9) << paired.faceCount() << " faces";
        EXPECT_EQ(pairTriangles(triangles).faceIndices, paired.faceIndices) << "not deterministic";
    }
}

// A paired cage (CageShape::Paired) is the triangle cage's decimation paired: about the faces
// asked, quad-dominant, on its reference.
TEST(TrianglePairing, APairedCageIsQuadDominantOnItsReference) {
    const mesh::PolygonMesh lumpy = mesh::makeLumpySphere(4, 0.15f, 3);
    const CageSource source(lumpy);
    const mesh::PolygonMesh cage = source.cage({.faces = 300, .shape = CageShape::Paired});
    EXPECT_GE(quadShare(cage), 0.9) << cage.faceCount() << " faces";
    EXPECT_GE(cage.faceCount(), 300);
    EXPECT_LT(cage.faceCount(), 360);
    float low = INFINITY, high = 0.0f;
    for (const glm::vec3& p : lumpy.positions)
        low = std::min(low, glm::length(p)), high = std::max(high, glm::length(p));
    for (const glm::vec3& p : limitPositionsOfVertices(cage, cage.positions)) {
        ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
        EXPECT_GT(glm::length(p), low - 0.02f);
        EXPECT_LT(glm::length(p), high + 0.02f);
    }
}

}  // namespace
}  // namespace subdfit::simplify
