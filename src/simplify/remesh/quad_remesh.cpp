#include "simplify/remesh/quad_remesh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "mesh/mesh_geometry.h"
#include "simplify/remesh/polygon_repair.h"
#include "simplify/remesh/quad_extraction.h"
#include "simplify/remesh/split_long_edges.h"
#include "simplify/remesh/surface_graph.h"
#include "util/error.h"

namespace subdfit::simplify::remesh {
namespace {

// Samples per quad edge the fields need: fewer, and a quad's region may hold no sample.
constexpr float kSamplesPerEdge = 2.0f;
// A remesh further than this from the vertices asked is made once more at a corrected spacing.
constexpr double kCountTolerance = 0.05;

// The edge length that makes the quads, one vertex to each edge length squared of surface,
// number about `vertices`.
float evenEdgeLength(const mesh::PolygonMesh& triangles, int vertices) {
    double area = 0.0;
    for (size_t c = 0; c + 2 < triangles.faceIndices.size(); c += 3) {
        const glm::vec3 p0 = triangles.positions[size_t(triangles.faceIndices[c])];
        area += 0.5 * double(glm::length(glm::cross(triangles.positions[size_t(triangles.faceIndices[c + 1])] - p0,
                                                    triangles.positions[size_t(triangles.faceIndices[c + 2])] - p0)));
    }
    if (!(area > 0.0)) throw fileError(triangles.sourcePath, "has no surface to remesh");
    return float(std::sqrt(area / double(vertices)));
}

}  // namespace

double QuadRemesh::quadShare() const {
    if (mesh.faceSizes.empty()) return 0.0;
    return double(mesh::quadCount(mesh)) / double(mesh.faceSizes.size());
}

QuadRemesh quadRemesh(const mesh::PolygonMesh& triangles, const QuadRemeshOptions& options) {
    if (options.vertices < 8) throw Error("a quad remesh needs at least 8 vertices");
    float edge = evenEdgeLength(triangles, options.vertices);
    const mesh::PolygonMesh samples = splitLongEdges(triangles, edge / kSamplesPerEdge);
    std::vector<GraphLevel> levels = surfaceHierarchy(samples, std::vector<float>(samples.positions.size(), edge));
    const std::vector<glm::vec3> orientation = orientationField(levels, options.sweeps);
    ExtractedMesh extracted =
        extractQuads(samples, levels[0], orientation, positionField(levels, orientation, options.sweeps));
    // The field's singularities and the regions' ragged edges lose some vertices: once, the
    // spacing that makes up for it.
    const double missing = double(options.vertices) / std::max(extracted.mesh.vertexCount(), 1);
    if (std::abs(missing - 1.0) > kCountTolerance) {
        edge /= float(std::sqrt(missing));
        for (GraphLevel& level : levels)
            for (float& scale : level.scales) scale = edge;
        extracted = extractQuads(samples, levels[0], orientation, positionField(levels, orientation, options.sweeps));
    }
    if (extracted.mesh.faceCount() == 0 || !isManifold(extracted.mesh))
        throw fileError(triangles.sourcePath, "its quad remesh is not a manifold mesh");
    return {std::move(extracted.mesh), std::move(extracted.normals), edge};
}

}  // namespace subdfit::simplify::remesh
