#include "simplify/limit_fit.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <optional>

#include "geometry/surface_queries.h"
#include "mesh/mesh_geometry.h"
#include "subdiv/limit_evaluator.h"
#include "util/interrupt.h"
#include "util/sparse_least_squares.h"

namespace subdfit::simplify {
namespace {

// Where the surface is sampled, and L: each sample's limit stencil over the cage vertices.
struct Samples {
    std::vector<int> ptexFace;
    std::vector<glm::vec2> uv;
    SparseRows stencils;
    size_t size() const { return ptexFace.size(); }
};

Samples samplesOf(const subdiv::LimitEvaluator& limit, int samplesPerEdge) {
    Samples samples;
    for (int f = 0; f < limit.ptexFaceCount(); ++f)
        for (int j = 0; j < samplesPerEdge; ++j)
            for (int i = 0; i < samplesPerEdge; ++i) {
                const glm::vec2 uv((float(i) + 0.5f) / float(samplesPerEdge), (float(j) + 0.5f) / float(samplesPerEdge));
                if (!limit.hasSurface(f, uv.x, uv.y)) continue;
                for (const auto& [v, w] : limit.positionWeights(f, uv.x, uv.y)) samples.stencils.add(v, w);
                samples.stencils.endRow();
                samples.ptexFace.push_back(f);
                samples.uv.push_back(uv);
            }
    return samples;
}

}  // namespace

LimitFitReport fitLimitToSurface(mesh::PolygonMesh& cage, const mesh::PolygonMesh& referenceTriangles,
                                 const LimitFitOptions& options) {
    LimitFitReport report;
    if (options.rounds <= 0 || referenceTriangles.faceCount() == 0) return report;
    const subdiv::LimitEvaluator limit(cage);
    const Samples L = samplesOf(limit, std::max(1, options.samplesPerEdge));
    const geometry::SurfaceQueries surface(referenceTriangles);
    const float reach = options.reach * mesh::meanEdgeLength(cage);
    report.samples = int(L.size());

    std::vector<glm::dvec3> P(cage.positions.begin(), cage.positions.end()), targets(L.size());
    std::vector<double> used(L.size());  // 1 for a sample that found the reference, else 0
    // Casts every sample of the surface at P along its normal; returns the RMS distance of the
    // samples that found the reference (the ones `used` then marks, with their `targets`).
    auto project = [&] {
        const std::vector<glm::vec3> positions(P.begin(), P.end());
        std::vector<glm::vec3> normals(L.size());
        std::vector<std::optional<geometry::RayHit>> hits(L.size());
        double agreement = 0.0;
        for (size_t s = 0; s < L.size(); ++s) {
            const subdiv::LimitSample at = limit.evaluate(L.ptexFace[s], L.uv[s].x, L.uv[s].y, positions);
            const glm::vec3 n = glm::cross(at.dPdu, at.dPdv);
            if (!(glm::length(n) > 1e-20f)) continue;
            normals[s] = glm::normalize(n);
            targets[s] = glm::dvec3(at.position);
            hits[s] = surface.castBothWays(at.position, normals[s], reach);
            if (!hits[s]) continue;
            const glm::vec3 faced = surface.triangleNormal(hits[s]->triangle);
            if (const float area = glm::length(faced); area > 0.0f) agreement += glm::dot(faced / area, normals[s]);
        }
        // Hits on a sheet facing against the surface are the far side of a thin part: pulling
        // onto them would fold the surface through itself; the sheet behind is the one.
        const float facing = agreement >= 0.0 ? 1.0f : -1.0f;
        double squares = 0.0;
        int count = 0;
        for (size_t s = 0; s < L.size(); ++s) {
            if (hits[s] && facing * glm::dot(surface.triangleNormal(hits[s]->triangle), normals[s]) <= 0.0f)
                hits[s] = surface.castFacing(glm::vec3(targets[s]), normals[s], reach, facing);
            used[s] = hits[s] && surface.reachesNearest(glm::vec3(targets[s]), *hits[s], options.detour * reach) ? 1.0 : 0.0;
            if (!used[s]) continue;
            targets[s] += double(hits[s]->distance) * glm::dvec3(normals[s]);
            squares += double(hits[s]->distance) * double(hits[s]->distance);
            ++count;
        }
        report.hits = count;
        return std::sqrt(squares / std::max(count, 1));
    };

    report.rmsBefore = project();
    for (int round = 0; round < options.rounds && report.hits > 0; ++round) {
        throwIfStopRequested();
        if (round > 0) project();
        P = solveDampedLeastSquares(L.stencils, targets, used, P, options.damping);
    }
    report.rmsAfter = project();
    for (size_t v = 0; v < P.size(); ++v) cage.positions[v] = glm::vec3(P[v]);
    return report;
}

}  // namespace subdfit::simplify
