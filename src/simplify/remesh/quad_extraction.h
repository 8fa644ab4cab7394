#pragma once
// The quad-dominant mesh a position field describes. The samples that share a lattice point
// (neighbours with no lattice step between them) are one output vertex; where the input's
// triangles meet three such regions they make an output triangle (the regions' dual, so the
// output inherits the input's connectivity and orientation); two output triangles that meet
// across a diagonal of the lattice are one quad. Overlapping triangles (where the field is
// disturbed, near its singularities) are dropped for the better-supported ones and the small
// holes they leave closed (simplify/remesh/polygon_repair.h).
#include <glm/vec3.hpp>
#include <vector>

#include "mesh/polygon_mesh.h"
#include "simplify/remesh/surface_graph.h"

namespace subdfit::simplify::remesh {

struct ExtractedMesh {
    mesh::PolygonMesh mesh;          // positions: each region's mean lattice point
    std::vector<glm::vec3> normals;  // each vertex's mean sample normal
};

// `triangles`: the mesh of `finest` (levels[0] of its hierarchy); `orientation`, `position`: the
// fields on its vertices.
ExtractedMesh extractQuads(const mesh::PolygonMesh& triangles, const GraphLevel& finest,
                           const std::vector<glm::vec3>& orientation, const std::vector<glm::vec3>& position);

}  // namespace subdfit::simplify::remesh
