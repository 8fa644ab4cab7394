#include "simplify/initial_cage.h"

#include <cmath>

#include "simplify/decimate.h"
#include "simplify/limit_fit.h"
#include "subdiv/limit_evaluator.h"
#include "util/error.h"
#include "util/interrupt.h"

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

// limit(P) at every base vertex, for any positions of one cage's topology.
class VertexLimits {
public:
    explicit VertexLimits(const mesh::PolygonMesh& cage) : evaluator_(cage), sites_(vertexSites(cage)) {}

    std::vector<glm::vec3> operator()(const std::vector<glm::vec3>& positions) const {
        std::vector<glm::vec3> limit(positions.size());
        for (size_t v = 0; v < positions.size(); ++v) {
            const VertexSite& s = sites_[v];
            limit[v] = s.ptexFace >= 0 && evaluator_.hasSurface(s.ptexFace, s.u, s.v)
                           ? evaluator_.evaluate(s.ptexFace, s.u, s.v, positions).position
                           : positions[v];
        }
        return limit;
    }

private:
    subdiv::LimitEvaluator evaluator_;
    std::vector<VertexSite> sites_;
};

}  // namespace

std::vector<glm::vec3> limitPositionsOfVertices(const mesh::PolygonMesh& cage, const std::vector<glm::vec3>& positions) {
    return VertexLimits(cage)(positions);
}

mesh::PolygonMesh initialCage(const mesh::PolygonMesh& reference, const InitialCageOptions& options) {
    const mesh::PolygonMesh welded = weldedTriangles(reference);
    mesh::PolygonMesh cage = decimate(welded, options.faces);
    cage.tags.triangles = mesh::TriangleSubdivision::Smooth;
    cage.tags.hasTriangles = true;
    cage.tags.boundary = mesh::BoundaryInterpolation::EdgeAndCorner;
    cage.tags.hasBoundary = true;
    if (cage.faceCount() < 2)
        throw fileError(reference.sourcePath, "too few faces survive decimation to make a cage");

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
    fitLimitToSurface(cage, welded, options.limitFit);
    for (const glm::vec3& p : cage.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw fileError(reference.sourcePath, "limit interpolation of the decimated cage diverged");
    return cage;
}

}  // namespace subdfit::simplify
