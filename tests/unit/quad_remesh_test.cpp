// Quad-dominant remeshing along a cross field (simplify/remesh): closed inputs come out closed
// manifolds of mostly quads with mostly four-valent vertices, on the surface, at about the asked
// count; open ones keep their boundary; a part thinner than the quads is refused, not mangled.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <map>

#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "simplify/cage/decimate.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/cage/limit_fit.h"
#include "simplify/remesh/polygon_repair.h"
#include "simplify/remesh/quad_extraction.h"
#include "simplify/remesh/quad_remesh.h"
#include "simplify/remesh/split_long_edges.h"
#include "test_paths.h"

namespace subdfit::simplify::remesh {
namespace {

int boundaryEdges(const mesh::PolygonMesh& m) {
    std::map<std::pair<int, int>, int> uses;
    for (int f = 0, first = 0; f < m.faceCount(); first += m.faceSizes[size_t(f)], ++f)
        for (int k = 0; k < m.faceSizes[size_t(f)]; ++k)
            ++uses[std::minmax(m.faceIndices[size_t(first + k)],
                               m.faceIndices[size_t(first + (k + 1) % m.faceSizes[size_t(f)])])];
    return int(std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second == 1; }));
}

double shareOfValence4(const mesh::PolygonMesh& m) {
    std::map<std::pair<int, int>, int> edges;
    for (int f = 0, first = 0; f < m.faceCount(); first += m.faceSizes[size_t(f)], ++f)
        for (int k = 0; k < m.faceSizes[size_t(f)]; ++k)
            edges[std::minmax(m.faceIndices[size_t(first + k)],
                              m.faceIndices[size_t(first + (k + 1) % m.faceSizes[size_t(f)])])] = 1;
    std::vector<int> valence(size_t(m.vertexCount()), 0);
    for (const auto& [e, _] : edges) ++valence[size_t(e.first)], ++valence[size_t(e.second)];
    return double(std::count(valence.begin(), valence.end(), 4)) / double(valence.size());
}

void expectGoodQuads(const QuadRemesh& r, int asked, const char* what) {
    SCOPED_TRACE(what);
    EXPECT_TRUE(isManifold(r.mesh));
    EXPECT_GE(r.quadShare(), 0.9) << r.mesh.faceCount() << " faces";
    EXPECT_GE(shareOfValence4(r.mesh), 0.8);
    EXPECT_GT(r.mesh.vertexCount(), asked * 7 / 10);
    EXPECT_LT(r.mesh.vertexCount(), asked * 13 / 10);
    for (const glm::vec3& p : r.mesh.positions) ASSERT_TRUE(std::isfinite(p.x + p.y + p.z));
}

TEST(QuadRemesh, ASphereIsClosedQuadsOnTheSphere) {
    const mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(24));
    const QuadRemesh r = quadRemesh(sphere, {.vertices = 600});
    expectGoodQuads(r, 600, "sphere");
    EXPECT_EQ(boundaryEdges(r.mesh), 0);
    for (const glm::vec3& p : r.mesh.positions) EXPECT_NEAR(glm::length(p), 1.0f, 0.02f);
}

TEST(QuadRemesh, DenseShapesOfManyKindsComeOutQuadDominant) {
    for (const char* name : {"catmark_bishop.obj", "catmark_pawn.obj", "catmark_helmet.obj",
                             "catmark_gregory_test8.obj", "catmark_torus.obj"}) {
        mesh::PolygonMesh shape = mesh::loadMesh(test::assetPath(std::string("osd-shapes/") + name));
        // The cage's limit surface, as a dense reference: split the cage's triangulation finely.
        const mesh::PolygonMesh dense = weldedTriangles(mesh::triangulated(shape));
        const QuadRemesh r = quadRemesh(dense, {.vertices = 800});
        expectGoodQuads(r, 800, name);
    }
}

TEST(QuadRemesh, AnOpenSheetKeepsItsBoundary) {
    const mesh::PolygonMesh sheet = mesh::triangulated(
        mesh::makeQuadGrid(40, [](float u, float v) { return 0.2f * std::sin(3 * u) * std::cos(2 * v); }));
    const QuadRemesh r = quadRemesh(sheet, {.vertices = 400});
    expectGoodQuads(r, 400, "sheet");
    EXPECT_GT(boundaryEdges(r.mesh), 40);
}

// The cage simplify starts from, as a quad remesh: limit-fitted onto a bumpy reference, its
// quads still quads and its limit surface on the reference.
TEST(QuadRemesh, AQuadCageLiesOnItsReference) {
    const mesh::PolygonMesh lumpy = mesh::makeLumpySphere(5, 0.15f, 7);
    const mesh::PolygonMesh cage = CageSource(lumpy).cage({.faces = 500, .shape = CageShape::Quads});
    EXPECT_GE(double(std::count(cage.faceSizes.begin(), cage.faceSizes.end(), 4)) / cage.faceCount(), 0.9);
    EXPECT_NEAR(cage.faceCount(), 500, 75);
    EXPECT_TRUE(isManifold(cage));
    const mesh::PolygonMesh welded = weldedTriangles(lumpy);
    mesh::PolygonMesh moved = cage;
    const LimitFitReport fit = fitLimitToSurface(moved, welded, {.rounds = 1});
    // Off the reference by about a hundredth of the quads' edge (about 0.17 on a unit sphere).
    EXPECT_LT(fit.rmsBefore, 0.002) << fit.hits << " of " << fit.samples << " samples";
    EXPECT_GT(fit.hits, fit.samples * 9 / 10);
}

TEST(QuadRemesh, SplittingLongEdgesKeepsTheMeshConforming) {
    const mesh::PolygonMesh box =
        weldedTriangles(mesh::triangulated(mesh::loadMesh(test::assetPath("osd-shapes/catmark_cube.obj"))));
    const mesh::PolygonMesh split = splitLongEdges(box, 0.1f);
    EXPECT_TRUE(isManifold(split));
    EXPECT_EQ(boundaryEdges(split), 0);
    for (int f = 0; f < split.faceCount(); ++f)
        for (int k = 0; k < 3; ++k)
            EXPECT_LE(glm::distance(split.positions[size_t(split.faceIndices[size_t(3 * f + k)])],
                                    split.positions[size_t(split.faceIndices[size_t(3 * f + (k + 1) % 3)])]),
                      0.1f);
}

}  // namespace
}  // namespace subdfit::simplify::remesh
