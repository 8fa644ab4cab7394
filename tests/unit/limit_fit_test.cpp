// The least-squares limit fit that finishes the initial cage (simplify/cage/limit_fit.h): it removes
// the ripples vertex interpolation leaves, keeps a surface that already fits, moves nothing it
// cannot see, and stays finite on creased and open cages.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <tbb/global_control.h>

#include <cmath>

#include "geometry/surface_distance.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "simplify/cage/decimate.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/cage/limit_fit.h"
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
    for (size_t v = 0; v < a.positions.size(); ++v)
        largest = std::max(largest, glm::length(a.positions[v] - b.positions[v]));
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

// A dense reference's cages are decimated from a copy of it decimated once (CageSource's
// mostFaces), not each from the whole reference: they lie as close to it, on the whole (case by
// case either may be closer, by a fifth or so).
TEST(CageSource, CagesFromItsDecimationCopyLieAsClose) {
    double logRatios = 0.0;
    int cases = 0;
    for (const std::uint32_t seed : {3u, 5u, 9u}) {
        const mesh::PolygonMesh reference = mesh::makeLumpySphere(5, 0.15f, seed);  // 20 480 triangles
        const mesh::PolygonMesh welded = weldedTriangles(reference);
        for (const int faces : {300, 800}) {
            const CageSource direct(reference), viaCopy(reference, true, faces);
            const mesh::PolygonMesh fromReference = direct.cage({.faces = faces}),
                                    fromCopy = viaCopy.cage({.faces = faces});
            EXPECT_NE(fromCopy.positions, fromReference.positions) << "the copy was decimated from";
            EXPECT_LE(fromCopy.faceCount(), faces);
            logRatios += std::log(meanDistance(fromCopy, welded) / meanDistance(fromReference, welded));
            // A cage grown past the ladder's top, from the copy too.
            const mesh::PolygonMesh grownFromCopy = viaCopy.cage({.faces = 2 * faces});
            EXPECT_NE(grownFromCopy.positions, direct.cage({.faces = 2 * faces}).positions);
            logRatios +=
                std::log(meanDistance(grownFromCopy, welded) / meanDistance(direct.cage({.faces = 2 * faces}), welded));
            cases += 2;
            if (seed == 3u && faces == 300) {  // more faces than the copy serves: from the reference
                EXPECT_EQ(viaCopy.cage({.faces = 900}).positions, direct.cage({.faces = 900}).positions);
            }
        }
    }
    EXPECT_LT(std::exp(logRatios / cases), 1.05) << "mean distance from the copy over from the reference";
}

// The rays are cast on every core: the cage must not depend on how many there are (the
// reductions keep their order), or two machines would ship different files from one input.
TEST(LimitFit, OneThreadAndManyGiveTheSameCage) {
    const mesh::PolygonMesh reference = weldedTriangles(mesh::makeLumpySphere(4, 0.15f, 9));
    mesh::PolygonMesh many = initialCage(reference, {.faces = 300, .limitFit = {.rounds = 0}}), one = many;
    fitLimitToSurface(many, reference);
    {
        const tbb::global_control serial(tbb::global_control::max_allowed_parallelism, 1);
        fitLimitToSurface(one, reference);
    }
    EXPECT_EQ(one.positions, many.positions);
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

// A tube: a quad grid wrapped around the z axis (its seam welds; its ends stay open).
mesh::PolygonMesh tube(int n) {
    mesh::PolygonMesh grid = mesh::triangulated(mesh::makeQuadGrid(n));
    for (glm::vec3& p : grid.positions) {
        const float angle = float(M_PI) * p.x;
        p = glm::vec3(std::cos(angle), std::sin(angle), 2.0f * p.y);
    }
    return weldedTriangles(grid);
}

// Mean of 4√3·area / Σ edge² over the triangles: 1 for equilateral ones, near 0 for slivers.
double meanTriangleQuality(const mesh::PolygonMesh& m) {
    double sum = 0.0;
    for (int f = 0; f < m.faceCount(); ++f) {
        const glm::vec3 a = m.positions[size_t(m.faceIndices[size_t(3 * f)])],
                        b = m.positions[size_t(m.faceIndices[size_t(3 * f + 1)])],
                        c = m.positions[size_t(m.faceIndices[size_t(3 * f + 2)])];
        const double edges = glm::dot(b - a, b - a) + glm::dot(c - b, c - b) + glm::dot(a - c, a - c);
        sum += edges > 0.0 ? 4.0 * std::sqrt(3.0) * 0.5 * glm::length(glm::cross(b - a, c - a)) / edges : 0.0;
    }
    return sum / std::max(m.faceCount(), 1);
}

// Quadric decimation of a tube leaves slivers along its axis; evening them out in the tangent
// plane gives rounder triangles and a surface at least as close.
TEST(InitialCageTriangles, SliversAreEvenedOut) {
    const mesh::PolygonMesh reference = tube(64);
    const mesh::PolygonMesh raw = initialCage(reference, {.faces = 200, .evenOutRounds = 0});
    const mesh::PolygonMesh even = initialCage(reference, {.faces = 200});
    EXPECT_GT(meanTriangleQuality(even), 1.1 * meanTriangleQuality(raw))
        << meanTriangleQuality(raw) << " -> " << meanTriangleQuality(even);
    EXPECT_LE(meanDistance(even, reference), 1.05 * meanDistance(raw, reference));
    EXPECT_TRUE(allFinite(even));
}

// A box [−1, 1]³ of n × n quads per side, triangulated and welded: sharp edges and corners.
mesh::PolygonMesh box(int n) {
    mesh::PolygonMesh all;
    for (int axis = 0; axis < 3; ++axis)
        for (const float side : {-1.0f, 1.0f}) {
            mesh::PolygonMesh grid = mesh::triangulated(mesh::makeQuadGrid(n));  // z = 0, facing +z
            for (glm::vec3& p : grid.positions) {
                glm::vec3 q(0.0f);
                q[axis] = side;
                q[(axis + 1) % 3] = side * p.x;  // mirrored on the −side, so every side faces out
                q[(axis + 2) % 3] = p.y;
                p = q;
            }
            const int offset = all.vertexCount();
            all.positions.insert(all.positions.end(), grid.positions.begin(), grid.positions.end());
            for (int i : grid.faceIndices) all.faceIndices.push_back(i + offset);
            all.faceSizes.insert(all.faceSizes.end(), grid.faceSizes.begin(), grid.faceSizes.end());
        }
    return weldedTriangles(all);
}

// Boundary vertices (the tube's open ends) and vertices on a feature (the box's edges and
// corners) stay where decimation put them; the others move only within their tangent plane.
TEST(InitialCageTriangles, FeaturesAndBoundariesStay) {
    for (const mesh::PolygonMesh& reference : {box(12), tube(48)}) {
        const InitialCageOptions evened{.faces = 150, .interpolationIterations = 0, .limitFit = {.rounds = 0}};
        InitialCageOptions kept = evened;
        kept.evenOutRounds = 0;
        const mesh::PolygonMesh moved = initialCage(reference, evened), decimated = initialCage(reference, kept);
        ASSERT_EQ(moved.faceIndices, decimated.faceIndices);
        const auto normals = mesh::vertexNormals(decimated);
        int pinned = 0;
        for (size_t v = 0; v < decimated.positions.size(); ++v) {
            const glm::vec3 p = decimated.positions[v];
            const bool onBoxEdge = int(std::abs(std::abs(p.x) - 1.0f) < 1e-5f) +
                                       int(std::abs(std::abs(p.y) - 1.0f) < 1e-5f) +
                                       int(std::abs(std::abs(p.z) - 1.0f) < 1e-5f) >=
                                   2;
            const bool onTubeEnd = std::abs(std::abs(p.z) - 2.0f) < 1e-5f;
            if (onBoxEdge || onTubeEnd) {
                EXPECT_EQ(moved.positions[v], p);
                ++pinned;
            }
            EXPECT_LT(std::abs(glm::dot(moved.positions[v] - p, normals[v])), 0.05f * mesh::meanEdgeLength(decimated));
        }
        EXPECT_GT(pinned, 8);
    }
}

}  // namespace
}  // namespace subdfit::simplify
