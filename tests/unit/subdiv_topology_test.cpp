// Building OpenSubdiv topology from a PolygonMesh: bad cages fail with an error naming the
// file, hard but legal ones (non-manifold, repeated vertices) build.
#include <gtest/gtest.h>

#include <opensubdiv/far/error.h>

#include <cmath>

#include "subdiv/limit_evaluator.h"
#include "subdiv/osd_messages.h"
#include "subdiv/patch_set.h"
#include "subdiv/topology.h"
#include "util/error.h"

namespace subdfit::subdiv {
namespace {

using mesh::PolygonMesh;

// Two quads side by side, named like a file so errors can be checked for the name.
PolygonMesh twoQuads() {
    PolygonMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 1, 0}};
    m.faceSizes = {4, 4};
    m.faceIndices = {0, 1, 4, 3, 1, 2, 5, 4};
    m.sourcePath = "cages/two_quads.obj";
    return m;
}

std::string errorOf(const PolygonMesh& mesh, int isolationLevel = 3) {
    try {
        buildPatchSet(mesh, {isolationLevel});
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

bool allFinite(const std::vector<glm::vec3>& points) {
    for (const glm::vec3& p : points)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
    return true;
}

TEST(SubdivTopology, SdcOptionsFollowTheTags) {
    mesh::SubdivisionTags tags;
    tags.boundary = mesh::BoundaryInterpolation::EdgeAndCorner;
    tags.faceVaryingBoundary = 4;
    tags.creaseMethod = mesh::CreaseMethod::Chaikin;
    tags.triangles = mesh::TriangleSubdivision::Smooth;
    using O = OpenSubdiv::Sdc::Options;
    const O options = sdcOptions(tags);
    EXPECT_EQ(options.GetVtxBoundaryInterpolation(), O::VTX_BOUNDARY_EDGE_AND_CORNER);
    EXPECT_EQ(options.GetFVarLinearInterpolation(), O::FVAR_LINEAR_BOUNDARIES);
    EXPECT_EQ(options.GetCreasingMethod(), O::CREASE_CHAIKIN);
    EXPECT_EQ(options.GetTriangleSubdivision(), O::TRI_SUB_SMOOTH);
    EXPECT_EQ(sdcOptions({}).GetVtxBoundaryInterpolation(), O::VTX_BOUNDARY_EDGE_ONLY);
}

TEST(SubdivTopology, BadIndicesFailNamingTheFile) {
    PolygonMesh outOfRange = twoQuads();
    outOfRange.faceIndices[5] = 6;
    EXPECT_EQ(errorOf(outOfRange), "cages/two_quads.obj: face vertex index 6 is out of range");

    PolygonMesh twoSided = twoQuads();
    twoSided.faceSizes = {4, 2, 2};
    EXPECT_EQ(errorOf(twoSided), "cages/two_quads.obj: face 1 has fewer than 3 vertices");

    PolygonMesh shortIndices = twoQuads();
    shortIndices.faceIndices.pop_back();
    EXPECT_NE(errorOf(shortIndices).find("do not add up"), std::string::npos);

    PolygonMesh badCrease = twoQuads();
    badCrease.tags.creases = {{1, 40, 10.0f}};
    EXPECT_NE(errorOf(badCrease).find("crease 1-40"), std::string::npos);

    PolygonMesh badHole = twoQuads();
    badHole.tags.holes = {2};
    EXPECT_NE(errorOf(badHole).find("hole face 2"), std::string::npos);

    PolygonMesh empty;
    EXPECT_EQ(errorOf(empty), "<in-memory mesh>: the cage has no vertices or no faces");
}

TEST(SubdivTopology, IsolationLevelIsChecked) {
    EXPECT_NE(errorOf(twoQuads(), 0).find("isolation level 0"), std::string::npos);
    EXPECT_NE(errorOf(twoQuads(), 11).find("isolation level 11"), std::string::npos);
    EXPECT_EQ(errorOf(twoQuads(), 10), "");
}

TEST(SubdivTopology, CreaseOnAMissingEdgeIsIgnoredQuietly) {
    PolygonMesh m = twoQuads();
    m.tags.creases = {{0, 5, 10.0f}};  // both vertices exist, no edge joins them
    testing::internal::CaptureStdout();
    EXPECT_EQ(errorOf(m), "");
    EXPECT_EQ(testing::internal::GetCapturedStdout(), "");
}

TEST(SubdivTopology, MessageScopeCollectsOpenSubdivReports) {
    OsdMessageScope outer;
    {
        OsdMessageScope inner;
        OpenSubdiv::Far::Error(OpenSubdiv::Far::FAR_RUNTIME_ERROR, "bad %s", "thing");
        OpenSubdiv::Far::Warning("odd %d", 7);
        EXPECT_EQ(inner.summary(), "bad thing; odd 7");
    }
    EXPECT_EQ(outer.summary(), "");
}

TEST(SubdivTopology, NonManifoldEdgeBuilds) {
    // Three quads hanging off one edge (0-1), like pages of a book.
    PolygonMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 0, 1}, {1, 0, 1}, {0, -1, 0}, {1, -1, 0}};
    m.faceSizes = {4, 4, 4};
    m.faceIndices = {0, 1, 3, 2, 1, 0, 4, 5, 0, 1, 7, 6};
    const PatchSet set = buildPatchSet(m);
    EXPECT_EQ(set.ptexFaceCount, 3);
    EXPECT_GT(set.patchCount(), 0);
    EXPECT_TRUE(allFinite(evaluatePoints(set, m.positions)));
    const LimitEvaluator evaluator(m);
    for (int f = 0; f < 3; ++f) {
        const LimitSample s = evaluator.evaluate(f, 0.5f, 0.5f, m.positions);
        EXPECT_TRUE(allFinite({s.position, s.dPdu, s.dPdv}));
    }
}

TEST(SubdivTopology, RepeatedVertexInAFaceBuilds) {
    PolygonMesh m = twoQuads();
    m.faceIndices = {0, 1, 4, 4, 1, 2, 5, 4};  // first quad collapses to a triangle
    const PatchSet set = buildPatchSet(m);
    EXPECT_TRUE(allFinite(evaluatePoints(set, m.positions)));
}

}  // namespace
}  // namespace subdfit::subdiv
