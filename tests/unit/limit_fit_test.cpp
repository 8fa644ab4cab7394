// The least-squares limit fit that finishes the initial cage (simplify/limit_fit.h): it removes
// the ripples vertex interpolation leaves, keeps a surface that already fits, moves nothing it
// cannot see, and stays finite on creased and open cages.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cmath>

#include "geometry/surface_distance.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "simplify/decimate.h"
#include "simplify/initial_cage.h"
#include "simplify/limit_fit.h"
#include "surface/tessellation.h"
#include "test_paths.h"

namespace subdfit::simplify {
namespace {

mesh::PolygonMesh limitTriangles(const mesh::PolygonMesh& cage, int segments = 6) {
    return surface::triangleMesh(surface::tessellate(cage, {}, segments));
}

double meanDistance(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference) {
    return geometry::surfaceDistance(limitTriangles(cage), reference, 20000).meanDistance;
}

float largestMove(const mesh::PolygonMesh& a, const mesh::PolygonMesh& b) {
    float largest = 0.0f;
    for (size_t v = 0; v < a.positions.size(); ++v) largest = std::max(largest, glm::length(a.positions[v] - b.positions[v]));
    return largest;
}

bool allFinite(const mesh::PolygonMesh& m) {
    for (const glm::vec3& p : m.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    return true;
}

// A dense triangle cage interpolating its vertices ripples between them; the fit over whole
// faces lies closer to the reference everywhere on average.
TEST(LimitFit, FitsCloserThanVertexInterpolation) {
    const mesh::PolygonMesh reference = weldedTriangles(mesh::makeLumpySphere(4, 0.15f, 9));
    const mesh::PolygonMesh interpolated = initialCage(reference, {.faces = 300, .limitFit = {.rounds = 0}});
    mesh::PolygonMesh fitted = interpolated;
    const LimitFitReport report = fitLimitToSurface(fitted, reference);
    EXPECT_GT(report.hits, report.samples * 9 / 10);
    EXPECT_LT(report.rmsAfter, 0.8 * report.rmsBefore);
    const double before = meanDistance(interpolated, reference), after = meanDistance(fitted, reference);
    EXPECT_LT(after, 0.8 * before) << "interpolated " << before << ", fitted " << after;
    // What initialCage returns by default is the fitted cage.
    EXPECT_EQ(initialCage(reference, {.faces = 300}).positions, fitted.positions);
}

// A reference that is the cage's own limit surface: the cage is (nearly) where it should be.
TEST(LimitFit, KeepsASurfaceThatAlreadyFits) {
    const mesh::PolygonMesh cage = mesh::loadMesh(test::assetPath("osd-shapes/catmark_bishop.obj"));
    const mesh::PolygonMesh reference = limitTriangles(cage, 16);
    mesh::PolygonMesh fitted = cage;
    const LimitFitReport report = fitLimitToSurface(fitted, reference);
    EXPECT_LE(report.rmsAfter, report.rmsBefore + 1e-6);
    EXPECT_LT(largestMove(fitted, cage), 0.02f * mesh::meanEdgeLength(cage));
}

// Samples that find no reference within reach pull nothing, and damping holds the rest.
TEST(LimitFit, NothingInReachMovesNothing) {
    const mesh::PolygonMesh cage = mesh::loadMesh(test::assetPath("osd-shapes/catmark_cube.obj"));
    mesh::PolygonMesh far = limitTriangles(cage);
    for (glm::vec3& p : far.positions) p += glm::vec3(100.0f, 0.0f, 0.0f);
    mesh::PolygonMesh fitted = cage;
    const LimitFitReport report = fitLimitToSurface(fitted, far);
    EXPECT_EQ(report.hits, 0);
    EXPECT_EQ(fitted.positions, cage.positions);
}

// Creases, corners, boundaries and holes: the fit towards a bumped copy of the limit surface
// stays finite and gets closer.
TEST(LimitFit, HardCagesStayFinite) {
    for (const char* name : {"catmark_cube_creases1.obj", "catmark_edgecorner.obj", "catmark_hole_test1.obj",
                             "catmark_torus_creases1.obj", "catmark_flap.obj"}) {
        SCOPED_TRACE(name);
        const mesh::PolygonMesh cage = mesh::loadMesh(test::assetPath(std::string("osd-shapes/") + name));
        mesh::PolygonMesh reference = limitTriangles(cage, 12);
        const auto normals = mesh::vertexNormals(reference);
        const float amplitude = 0.05f * mesh::meanEdgeLength(cage);
        for (size_t v = 0; v < reference.positions.size(); ++v)
            reference.positions[v] += amplitude * (1.0f + std::sin(7.0f * reference.positions[v].x)) * normals[v];
        mesh::PolygonMesh fitted = cage;
        const LimitFitReport report = fitLimitToSurface(fitted, reference);
        EXPECT_TRUE(allFinite(fitted));
        EXPECT_LT(report.rmsAfter, report.rmsBefore);
    }
}

}  // namespace
}  // namespace subdfit::simplify
