#include "simplify/cage/initial_cage.h"

#include <cmath>
#include <algorithm>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/mesh_adjacency.h"
#include "mesh/mesh_geometry.h"
#include "simplify/cage/decimate.h"
#include "simplify/cage/feature_edges.h"
#include "simplify/cage/limit_fit.h"
#include "simplify/cage/triangle_pairing.h"
#include "simplify/remesh/quad_remesh.h"
#include "subdiv/limit_evaluator.h"
#include "util/error.h"
#include "util/interrupt.h"
#include "util/sparse_least_squares.h"
#include "util/warnings.h"

namespace subdfit::simplify {
namespace {

// A ptex face and corner at which each base vertex sits: a quad is one ptex face with its
// vertices at (0,0), (1,0), (1,1), (0,1); an n-gon is n ptex faces, sub-face k starting at
// (0,0) on vertex k (OpenSubdiv's ptex convention).
struct VertexSite {
    int ptexFace = -1;
    float u = 0.0f, v = 0.0f;
};

std::vector<VertexSite> vertexSites(const mesh::PolygonMesh& cage) {
    static constexpr float kQuadCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    std::vector<VertexSite> sites(size_t(cage.vertexCount()));
    int ptex = 0, first = 0;
    for (int f = 0; f < cage.faceCount(); ++f) {
        const int n = cage.faceSizes[size_t(f)];
        for (int k = 0; k < n; ++k) {
            VertexSite& site = sites[size_t(cage.faceIndices[size_t(first + k)])];
            if (site.ptexFace >= 0) continue;
            site = n == 4 ? VertexSite{ptex, kQuadCorner[k][0], kQuadCorner[k][1]} : VertexSite{ptex + k, 0.0f, 0.0f};
        }
        ptex += n == 4 ? 1 : n;
        first += n;
    }
    return sites;
}

// limit(P) at every base vertex, for any positions of one cage's topology: each vertex's limit
// stencil over the base vertices, found once (the surface is linear in its cage).
class VertexLimits {
public:
    explicit VertexLimits(const mesh::PolygonMesh& cage) {
        const subdiv::LimitEvaluator evaluator(cage);
        const std::vector<VertexSite> sites = vertexSites(cage);
        onSurface_.assign(sites.size(), 0);
        for (size_t v = 0; v < sites.size(); ++v) {
            const VertexSite& s = sites[v];
            onSurface_[v] = s.ptexFace >= 0 && evaluator.hasSurface(s.ptexFace, s.u, s.v);
            if (onSurface_[v])
                for (const auto& [vertex, weight] : evaluator.positionWeights(s.ptexFace, s.u, s.v))
                    stencils_.add(vertex, weight);
            stencils_.endRow();
        }
    }

    std::vector<glm::vec3> operator()(const std::vector<glm::vec3>& positions) const {
        const std::vector<glm::dvec3> at(positions.begin(), positions.end());
        std::vector<glm::vec3> limit(positions.size());
        for (size_t v = 0; v < positions.size(); ++v)
            limit[v] = onSurface_[v] ? glm::vec3(stencils_.apply(v, at)) : positions[v];
        return limit;
    }

private:
    SparseRows stencils_;  // row v: vertex v's limit position (empty off the surface)
    std::vector<char> onSurface_;
};

// Vertices that must not slide: on a boundary (an edge not shared by two faces) or on a feature
// (an incident face turned more than ~35° from the vertex normal, or of no area: decimation
// leaves zero-area faces along sharp edges, hiding them from the vertex normal).
std::vector<char> pinnedVertices(const mesh::PolygonMesh& triangles, const std::vector<glm::vec3>& normals) {
    std::vector<char> pinned(triangles.positions.size(), 0);
    std::map<std::pair<int, int>, int> edgeUse;
    for (int f = 0; f < triangles.faceCount(); ++f) {
        const int* v = &triangles.faceIndices[size_t(3 * f)];
        for (int k = 0; k < 3; ++k) ++edgeUse[std::minmax(v[k], v[(k + 1) % 3])];
        const glm::vec3 e1 = triangles.positions[size_t(v[1])] - triangles.positions[size_t(v[0])],
                        e2 = triangles.positions[size_t(v[2])] - triangles.positions[size_t(v[0])];
        const glm::vec3 faceNormal = glm::cross(e1, e2);
        const float length = glm::length(faceNormal);
        const bool degenerate = !(length > 1e-6f * (glm::dot(e1, e1) + glm::dot(e2, e2)));
        for (int k = 0; k < 3; ++k)
            if (degenerate || glm::dot(faceNormal / length, normals[size_t(v[k])]) < 0.82f) pinned[size_t(v[k])] = 1;
    }
    for (const auto& [edge, use] : edgeUse)
        if (use != 2) pinned[size_t(edge.first)] = pinned[size_t(edge.second)] = 1;
    return pinned;
}

// Decimation by quadrics leaves slivers where the surface is flat in one direction (long thin
// triangles along a cylinder's axis), and a Catmull-Clark surface wrinkles over them. Each round
// moves every vertex that is not pinned halfway to its neighbours' centroid within its tangent
// plane, so creases and rims keep their place.
void evenOutTriangles(mesh::PolygonMesh& triangles, int rounds) {
    const mesh::VertexAdjacency adjacency = mesh::vertexAdjacency(triangles);
    for (int round = 0; round < rounds; ++round) {
        const std::vector<glm::vec3> normals = mesh::vertexNormals(triangles);
        const std::vector<char> pinned = pinnedVertices(triangles, normals);
        std::vector<glm::vec3> moved = triangles.positions;
        for (size_t v = 0; v < moved.size(); ++v) {
            const int first = adjacency.offsets[v], last = adjacency.offsets[v + 1];
            if (pinned[v] || last == first) continue;
            glm::vec3 centroid(0.0f);
            for (int k = first; k < last; ++k) centroid += triangles.positions[size_t(adjacency.neighbors[size_t(k)])];
            glm::vec3 step = centroid / float(last - first) - triangles.positions[v];
            step -= normals[v] * glm::dot(normals[v], step);
            moved[v] += 0.5f * step;
        }
        triangles.positions = std::move(moved);
    }
}

}  // namespace

std::vector<glm::vec3> limitPositionsOfVertices(const mesh::PolygonMesh& cage,
                                                const std::vector<glm::vec3>& positions) {
    return VertexLimits(cage)(positions);
}

mesh::PolygonMesh initialCage(const mesh::PolygonMesh& reference, const InitialCageOptions& options) {
    return CageSource(reference, options.hardEdges, options.faces).cage(options);
}

CageSource::CageSource(const mesh::PolygonMesh& reference, bool hardEdges, int mostFaces)
    : reference_(reference),
      welded_(weldedTriangles(reference)),
      surface_(std::make_unique<geometry::SurfaceQueries>(welded_)) {
    if (hardEdges) hardEdges_.emplace(mesh::triangulated(reference));
    const int copyFaces = kDecimationCopyFactor * mostFaces;
    if (mostFaces > 0 && welded_.faceCount() > 2 * copyFaces) {
        decimationCopy_ = decimate(welded_, copyFaces);
        copyServes_ = 2 * mostFaces;
    }
}

std::optional<mesh::PolygonMesh> CageSource::quadCage(int faces) const {
    const bool fromCopy = decimationCopy_ && faces <= copyServes_;
    const mesh::PolygonMesh& input = fromCopy ? *decimationCopy_ : welded_;
    remesh::QuadRemesh remeshed;
    try {
        remeshed = remesh::quadRemesh(input, {.vertices = std::max(8, faces)});
    } catch (const Error& e) {
        warn(std::string(e.what()) + ": the cage is decimated instead");
        return std::nullopt;
    }
    // The regions' mean lattice points lie in tangent planes: onto the reference along the normal.
    mesh::PolygonMesh cage = std::move(remeshed.mesh);
    for (size_t v = 0; v < cage.positions.size(); ++v)
        if (const auto hit = surface_->castBothWays(cage.positions[v], remeshed.normals[v], remeshed.edgeLength))
            cage.positions[v] += remeshed.normals[v] * hit->distance;
    return cage;
}

mesh::PolygonMesh CageSource::decimatedCage(const InitialCageOptions& options) const {
    const bool fromCopy = decimationCopy_ && options.faces <= copyServes_;
    mesh::PolygonMesh cage = decimate(fromCopy ? *decimationCopy_ : welded_, options.faces);
    // While the decimated vertices still lie on the reference, where its hard edges are.
    if (options.hardEdges && hardEdges_) hardEdges_->tag(cage);
    evenOutTriangles(cage, options.evenOutRounds);
    return cage;
}

mesh::PolygonMesh CageSource::cage(const InitialCageOptions& options) const {
    std::optional<mesh::PolygonMesh> quads;
    if (options.shape == CageShape::Quads) quads = quadCage(options.faces);
    if (options.shape == CageShape::Paired) {
        InitialCageOptions triangles = options;
        triangles.faces = 2 * options.faces;
        quads = pairTriangles(decimatedCage(triangles));
    }
    mesh::PolygonMesh cage = quads ? std::move(*quads) : decimatedCage(options);
    if (cage.faceCount() < 2) throw fileError(reference_.sourcePath, "too few faces survive decimation to make a cage");
    cage.sourcePath = reference_.sourcePath;
    cage.tags.triangles = mesh::TriangleSubdivision::Smooth;
    cage.tags.hasTriangles = true;
    cage.tags.boundary = mesh::BoundaryInterpolation::EdgeAndCorner;
    cage.tags.hasBoundary = true;

    // Jacobi on limit(P) = V: the limit masks are convex combinations with the vertex itself
    // weighted most, so I − L contracts and a few sweeps converge.
    const std::vector<glm::vec3> targets = cage.positions;
    const VertexLimits limitOf(cage);
    for (int i = 0; i < options.interpolationIterations; ++i) {
        throwIfStopRequested();
        const auto limit = limitOf(cage.positions);
        for (size_t v = 0; v < targets.size(); ++v) cage.positions[v] += targets[v] - limit[v];
    }
    // Interpolation pins the vertices; between them an approximating surface overshoots
    // (ripples on a dense triangle cage). The least-squares fit over whole faces settles it.
    LimitFitOptions limitFit = options.limitFit;
    limitFit.measureAfter = false;  // nothing here reads how close it came
    fitLimitToSurface(cage, welded_, *surface_, limitFit);
    for (const glm::vec3& p : cage.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw fileError(reference_.sourcePath, "limit interpolation of the initial cage diverged");
    return cage;
}

}  // namespace subdfit::simplify
