#pragma once
// A triangle mesh with no edge longer than a length: a remesher's fields need samples finer than
// the quads they describe, and a decimated input keeps large triangles where it is flat.
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify::remesh {

// Each pass splits every edge longer than `longest` at its midpoint, and each triangle into the
// 2, 3 or 4 its split edges make (the mesh stays conforming), until none is longer.
mesh::PolygonMesh splitLongEdges(const mesh::PolygonMesh& triangles, float longest);

}  // namespace subdfit::simplify::remesh
