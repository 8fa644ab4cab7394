#include "simplify/remesh/quad_remesh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "simplify/remesh/polygon_repair.h"
#include "simplify/remesh/quad_extraction.h"
#include "simplify/remesh/split_long_edges.h"
#include "simplify/remesh/surface_graph.h"
#include "util/error.h"

namespace subdfit::simplify::remesh {
namespace {

// Samples per quad edge the fields need: fewer, and a quad's region may hold no sample.
constexpr float kSamplesPerEdge = 3.0f;
constexpr double kCountTolerance = 0.05;

// A third of each triangle's area to each of its vertices.
std::vector<double> vertexAreas(const mesh::PolygonMesh& triangles) {
    std::vector<double> areas(triangles.positions.size(), 0.0);
    for (size_t c = 0; c + 2 < triangles.faceIndices.size(); c += 3) {
        const int* v = &triangles.faceIndices[c];
        const glm::vec3 p0 = triangles.positions[size_t(v[0])];
        const double third = double(glm::length(glm::cross(triangles.positions[size_t(v[1])] - p0,
                                                           triangles.positions[size_t(v[2])] - p0))) / 6.0;
        for (int k = 0; k < 3; ++k) areas[size_t(v[k])] += third;
    }
    return areas;
}

// The edge length at each vertex: `relative` (or even) scaled so that the quads, one vertex to
// each edge length squared of surface, number about `vertices`.
std::vector<float> edgeLengths(const mesh::PolygonMesh& triangles, const std::vector<float>& relative, int vertices) {
    const std::vector<double> areas = vertexAreas(triangles);
    std::vector<float> lengths(areas.size(), 1.0f);
    if (relative.size() == lengths.size())
        for (size_t v = 0; v < lengths.size(); ++v) lengths[v] = std::isfinite(relative[v]) && relative[v] > 0.0f ? relative[v] : 1.0f;
    double quads = 0.0;  // at factor 1
    for (size_t v = 0; v < areas.size(); ++v) quads += areas[v] / (double(lengths[v]) * lengths[v]);
    if (!(quads > 0.0)) throw fileError(triangles.sourcePath, "has no surface to remesh");
    const float factor = float(std::sqrt(quads / double(vertices)));
    for (float& length : lengths) length *= factor;
    return lengths;
}

}  // namespace

double QuadRemesh::quadShare() const {
    if (mesh.faceSizes.empty()) return 0.0;
    return double(std::count(mesh.faceSizes.begin(), mesh.faceSizes.end(), 4)) / double(mesh.faceSizes.size());
}

QuadRemesh quadRemesh(const mesh::PolygonMesh& triangles, const QuadRemeshOptions& options) {
    if (options.vertices < 8) throw Error("a quad remesh needs at least 8 vertices");
    std::vector<float> lengths = edgeLengths(triangles, options.relativeEdge, options.vertices);
    const float longestEdge = *std::max_element(lengths.begin(), lengths.end());
    for (float& length : lengths) length /= kSamplesPerEdge;
    const mesh::PolygonMesh samples = splitLongEdges(triangles, lengths);
    for (float& length : lengths) length *= kSamplesPerEdge;
    std::vector<GraphLevel> levels = surfaceHierarchy(samples, std::move(lengths));
    const std::vector<glm::vec3> orientation = orientationField(levels, options.sweeps);
    ExtractedMesh extracted = extractQuads(samples, levels[0], orientation, positionField(levels, orientation, options.sweeps));
    // Singularities and the seams where spacing changes lose some vertices: once, the spacing
    // that makes up for it.
    const double missing = double(options.vertices) / std::max(extracted.mesh.vertexCount(), 1);
    if (std::abs(missing - 1.0) > kCountTolerance) {
        for (GraphLevel& level : levels)
            for (float& scale : level.scales) scale /= float(std::sqrt(missing));
        extracted = extractQuads(samples, levels[0], orientation, positionField(levels, orientation, options.sweeps));
    }
    if (extracted.mesh.faceCount() == 0 || !isManifold(extracted.mesh))
        throw fileError(triangles.sourcePath, "its quad remesh is not a manifold mesh");
    return {std::move(extracted.mesh), std::move(extracted.normals), longestEdge};
}

}  // namespace subdfit::simplify::remesh
