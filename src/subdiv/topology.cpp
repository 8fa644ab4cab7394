#include "subdiv/topology.h"

#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mesh/input_limits.h"
#include "subdiv/osd_messages.h"
#include "util/error.h"

namespace subdfit::subdiv {
namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

// OpenSubdiv trusts its indices (an out-of-range one is undefined behaviour, not an error
// report), so everything that indexes is checked here first.
void checkIndices(const mesh::PolygonMesh& mesh) {
    const auto fail = [&](const std::string& problem) { throw fileError(meshName(mesh), problem); };
    const int vertexCount = mesh.vertexCount(), faceCount = mesh.faceCount();
    const auto isVertex = [&](int v) { return v >= 0 && v < vertexCount; };
    if (vertexCount == 0 || faceCount == 0) fail("the cage has no vertices or no faces");

    if (std::accumulate(mesh.faceSizes.begin(), mesh.faceSizes.end(), std::size_t(0)) != mesh.faceIndices.size())
        fail("face sizes do not add up to the number of face indices");
    for (int f = 0; f < faceCount; ++f) {
        if (mesh.faceSizes[f] < 3) fail("face " + std::to_string(f) + " has fewer than 3 vertices");
        if (mesh.faceSizes[f] > mesh::kMaxCageFaceSize)
            fail("face " + std::to_string(f) + " has " + std::to_string(mesh.faceSizes[f]) +
                 " vertices; a cage face may have at most " + std::to_string(mesh::kMaxCageFaceSize) +
                 " (the limit surface around it costs time growing with the cube of its size): split it");
    }
    std::vector<int> valence(size_t(vertexCount), 0);
    for (int v : mesh.faceIndices) {
        if (!isVertex(v)) fail("face vertex index " + std::to_string(v) + " is out of range");
        if (++valence[size_t(v)] > mesh::kMaxCageValence)
            fail("vertex " + std::to_string(v) + " is shared by more than " + std::to_string(mesh::kMaxCageValence) +
                 " faces, the most a cage vertex may have (the limit surface around it costs time growing with the "
                 "cube of its valence)");
    }
    if (mesh.tags.holes.size() >= size_t(faceCount)) {
        std::vector<char> hole(size_t(faceCount), 0);
        for (int h : mesh.tags.holes)
            if (h >= 0 && h < faceCount) hole[size_t(h)] = 1;
        if (std::count(hole.begin(), hole.end(), 1) == faceCount)
            fail("every face is tagged as a hole: nothing to render");
    }

    const auto isSharpness = [](float s) { return std::isfinite(s) && s >= 0.0f; };
    for (const mesh::Crease& c : mesh.tags.creases)
        if (!isVertex(c.v0) || !isVertex(c.v1) || !isSharpness(c.sharpness))
            fail("crease " + std::to_string(c.v0) + "-" + std::to_string(c.v1) +
                 " has a vertex out of range or a bad sharpness");
    for (const mesh::Corner& c : mesh.tags.corners)
        if (!isVertex(c.vertex) || !isSharpness(c.sharpness))
            fail("corner " + std::to_string(c.vertex) + " is out of range or has a bad sharpness");
    for (int h : mesh.tags.holes)
        if (h < 0 || h >= faceCount) fail("hole face " + std::to_string(h) + " is out of range");
}

Sdc::Options::FVarLinearInterpolation fvarInterpolation(int tag) {
    using O = Sdc::Options;
    switch (tag) {
        case 0: return O::FVAR_LINEAR_NONE;
        case 1: return O::FVAR_LINEAR_CORNERS_ONLY;
        case 2: return O::FVAR_LINEAR_CORNERS_PLUS1;
        case 3: return O::FVAR_LINEAR_CORNERS_PLUS2;
        case 4: return O::FVAR_LINEAR_BOUNDARIES;
        default: return O::FVAR_LINEAR_ALL;
    }
}

}  // namespace

int ptexFaceCount(const mesh::PolygonMesh& mesh) {
    int count = 0;
    for (int n : mesh.faceSizes) count += n == 4 ? 1 : n;
    return count;
}

std::string meshName(const mesh::PolygonMesh& mesh) {
    return mesh.sourcePath.empty() ? std::string("<in-memory mesh>") : mesh.sourcePath;
}

Sdc::Options sdcOptions(const mesh::SubdivisionTags& tags) {
    using O = Sdc::Options;
    O options;
    switch (tags.boundary) {
        case mesh::BoundaryInterpolation::None: options.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_NONE); break;
        case mesh::BoundaryInterpolation::EdgeAndCorner:
            options.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_EDGE_AND_CORNER);
            break;
        case mesh::BoundaryInterpolation::EdgeOnly:
            options.SetVtxBoundaryInterpolation(O::VTX_BOUNDARY_EDGE_ONLY);
            break;
    }
    options.SetFVarLinearInterpolation(fvarInterpolation(tags.faceVaryingBoundary));
    options.SetCreasingMethod(tags.creaseMethod == mesh::CreaseMethod::Chaikin ? O::CREASE_CHAIKIN : O::CREASE_UNIFORM);
    options.SetTriangleSubdivision(tags.triangles == mesh::TriangleSubdivision::Smooth ? O::TRI_SUB_SMOOTH
                                                                                       : O::TRI_SUB_CATMARK);
    return options;
}

RefinerPtr buildTopologyRefiner(const mesh::PolygonMesh& mesh) {
    checkIndices(mesh);

    const mesh::SubdivisionTags& tags = mesh.tags;
    std::vector<int> creasePairs;
    std::vector<float> creaseWeights;
    for (const mesh::Crease& c : tags.creases) {
        creasePairs.insert(creasePairs.end(), {c.v0, c.v1});
        creaseWeights.push_back(c.sharpness);
    }
    std::vector<int> cornerVertices;
    std::vector<float> cornerWeights;
    for (const mesh::Corner& c : tags.corners) {
        cornerVertices.push_back(c.vertex);
        cornerWeights.push_back(c.sharpness);
    }

    Far::TopologyDescriptor desc;
    desc.numVertices = mesh.vertexCount();
    desc.numFaces = mesh.faceCount();
    desc.numVertsPerFace = mesh.faceSizes.data();
    desc.vertIndicesPerFace = mesh.faceIndices.data();
    desc.numCreases = int(creaseWeights.size());
    desc.creaseVertexIndexPairs = creasePairs.data();
    desc.creaseWeights = creaseWeights.data();
    desc.numCorners = int(cornerWeights.size());
    desc.cornerVertexIndices = cornerVertices.data();
    desc.cornerWeights = cornerWeights.data();
    desc.numHoles = int(tags.holes.size());
    desc.holeIndices = tags.holes.data();

    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    OsdMessageScope messages;
    RefinerPtr refiner(Factory::Create(desc, Factory::Options(OpenSubdiv::Sdc::SCHEME_CATMARK, sdcOptions(tags))));
    if (!refiner) {
        const std::string why = messages.summary();
        throw fileError(meshName(mesh),
                        "OpenSubdiv rejected the cage topology" + (why.empty() ? std::string() : ": " + why));
    }
    return refiner;
}

}  // namespace subdfit::subdiv
