#pragma once
// The limit surface of a cage as a plain triangle mesh (CPU, OpenSubdiv evaluation): the
// reference for synthetic tests, and the surface that geometric error is measured on.
#include <span>

#include "mesh/polygon_mesh.h"

namespace subdfit::geometry {

// `segments`² quads (two triangles each) per ptex face; vertices shared along face borders are
// welded, so vertexNormals() of the result is smooth. Holes are left out.
mesh::PolygonMesh limitMesh(const mesh::PolygonMesh& cage, int segments);

}  // namespace subdfit::geometry
