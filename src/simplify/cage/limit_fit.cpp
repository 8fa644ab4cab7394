#include "simplify/cage/limit_fit.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "geometry/normal_casting.h"
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
    // Faces in chunks on every core, each chunk's samples appended in the faces' order.
    constexpr int kFacesPerChunk = 256;
    std::vector<Samples> chunks(size_t((limit.ptexFaceCount() + kFacesPerChunk - 1) / kFacesPerChunk));
    tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
        Samples& chunk = chunks[c];
        const int end = std::min(limit.ptexFaceCount(), int(c + 1) * kFacesPerChunk);
        for (int f = int(c) * kFacesPerChunk; f < end; ++f)
            for (int j = 0; j < samplesPerEdge; ++j)
                for (int i = 0; i < samplesPerEdge; ++i) {
                    const glm::vec2 uv((float(i) + 0.5f) / float(samplesPerEdge),
                                       (float(j) + 0.5f) / float(samplesPerEdge));
                    if (!limit.hasSurface(f, uv.x, uv.y)) continue;
                    for (const auto& [v, w] : limit.positionWeights(f, uv.x, uv.y)) chunk.stencils.add(v, w);
                    chunk.stencils.endRow();
                    chunk.ptexFace.push_back(f);
                    chunk.uv.push_back(uv);
                }
    });
    Samples samples;
    for (const Samples& chunk : chunks) {
        samples.stencils.append(chunk.stencils);
        samples.ptexFace.insert(samples.ptexFace.end(), chunk.ptexFace.begin(), chunk.ptexFace.end());
        samples.uv.insert(samples.uv.end(), chunk.uv.begin(), chunk.uv.end());
    }
    return samples;
}

}  // namespace

LimitFitReport fitLimitToSurface(mesh::PolygonMesh& cage, const mesh::PolygonMesh& referenceTriangles,
                                 const LimitFitOptions& options) {
    if (options.rounds <= 0 || referenceTriangles.faceCount() == 0) return {};
    return fitLimitToSurface(cage, referenceTriangles, geometry::SurfaceQueries(referenceTriangles), options);
}

LimitFitReport fitLimitToSurface(mesh::PolygonMesh& cage, const mesh::PolygonMesh& referenceTriangles,
                                 const geometry::SurfaceQueries& surface, const LimitFitOptions& options) {
    LimitFitReport report;
    if (options.rounds <= 0 || referenceTriangles.faceCount() == 0) return report;
    const subdiv::LimitEvaluator limit(cage);
    const Samples L = samplesOf(limit, std::max(1, options.samplesPerEdge));
    const float reach = options.reach * mesh::meanEdgeLength(cage);
    report.samples = int(L.size());

    std::vector<glm::dvec3> P(cage.positions.begin(), cage.positions.end()), targets(L.size());
    std::vector<double> used(L.size());  // 1 for a sample that found the reference, else 0
    // Casts every sample of the surface at P along its normal; returns the RMS distance of the
    // samples that found the reference (the ones `used` then marks, with their `targets`).
    auto project = [&] {
        const std::vector<glm::vec3> positions(P.begin(), P.end());
        const std::vector<glm::dvec3> points = limit.patchPoints(positions);
        std::vector<glm::vec3> origins(L.size()), normals(L.size());
        tbb::parallel_for(size_t(0), L.size(), [&](size_t s) {
            const subdiv::LimitSample at = limit.evaluate(L.ptexFace[s], L.uv[s].x, L.uv[s].y, points);
            const glm::vec3 n = glm::cross(at.dPdu, at.dPdv);
            origins[s] = at.position;
            normals[s] = glm::length(n) > 1e-20f ? glm::normalize(n) : glm::vec3(0.0f);
        });
        const geometry::NormalCasts casts =
            geometry::castAlongNormals(surface, origins, normals, reach, options.detour * reach);
        double squares = 0.0;
        report.hits = 0;
        for (size_t s = 0; s < L.size(); ++s) {
            used[s] = casts.hits[s] ? 1.0 : 0.0;
            if (!casts.hits[s]) continue;
            const double distance = casts.hits[s]->distance;
            targets[s] = glm::dvec3(origins[s]) + distance * glm::dvec3(normals[s]);
            squares += distance * distance;
            ++report.hits;
        }
        return std::sqrt(squares / std::max(report.hits, 1));
    };

    report.rmsBefore = project();
    for (int round = 0; round < options.rounds && report.hits > 0; ++round) {
        throwIfStopRequested();
        if (round > 0) project();
        P = solveDampedLeastSquares(L.stencils, targets, used, P, options.damping);
    }
    if (options.measureAfter) report.rmsAfter = project();
    for (size_t v = 0; v < P.size(); ++v) cage.positions[v] = glm::vec3(P[v]);
    return report;
}

}  // namespace subdfit::simplify
