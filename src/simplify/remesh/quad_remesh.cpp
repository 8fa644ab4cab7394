#include "simplify/remesh/quad_remesh.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "simplify/remesh/quad_extraction.h"
#include "simplify/remesh/split_long_edges.h"
#include "simplify/remesh/surface_graph.h"
#include "util/error.h"

namespace subdfit::simplify::remesh {
namespace {

// Samples per quad edge the fields need: fewer, and a quad's region may hold no sample.
constexpr float kSamplesPerEdge = 3.0f;

double surfaceArea(const mesh::PolygonMesh& triangles) {
    double area = 0.0;
    for (size_t c = 0; c + 2 < triangles.faceIndices.size(); c += 3) {
        const glm::vec3 p0 = triangles.positions[size_t(triangles.faceIndices[c])];
        area += 0.5 * double(glm::length(glm::cross(triangles.positions[size_t(triangles.faceIndices[c + 1])] - p0,
                                                    triangles.positions[size_t(triangles.faceIndices[c + 2])] - p0)));
    }
    return area;
}

}  // namespace

double QuadRemesh::quadShare() const {
    if (mesh.faceSizes.empty()) return 0.0;
    return double(std::count(mesh.faceSizes.begin(), mesh.faceSizes.end(), 4)) / double(mesh.faceSizes.size());
}

QuadRemesh quadRemesh(const mesh::PolygonMesh& triangles, const QuadRemeshOptions& options) {
    if (options.vertices < 8) throw Error("a quad remesh needs at least 8 vertices");
    const double area = surfaceArea(triangles);
    if (!(area > 0.0)) throw fileError(triangles.sourcePath, "has no surface to remesh");
    const float scale = float(std::sqrt(area / double(options.vertices)));
    const mesh::PolygonMesh samples = splitLongEdges(triangles, scale / kSamplesPerEdge);
    const std::vector<GraphLevel> levels = surfaceHierarchy(samples);
    const std::vector<glm::vec3> orientation = orientationField(levels, options.sweeps);
    const std::vector<glm::vec3> position = positionField(levels, orientation, scale, options.sweeps);
    ExtractedMesh extracted = extractQuads(samples, levels[0], orientation, position, scale);
    if (extracted.mesh.faceCount() == 0 || !isManifold(extracted.mesh))
        throw fileError(triangles.sourcePath, "its quad remesh is not a manifold mesh");
    return {std::move(extracted.mesh), std::move(extracted.normals), scale};
}

}  // namespace subdfit::simplify::remesh
