#pragma once
// Making a set of consistently oriented polygons a manifold mesh: where a remesher's extraction
// drops overlapping faces it leaves vertices whose faces form two fans (touching at a point) and
// holes its input does not have.
#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::simplify::remesh {

using Polygons = std::vector<std::vector<int>>;  // each a face's vertices, in order

// Gives every fan of faces around a vertex but its first a vertex of its own (faces that share
// an edge the opposite ways are in one fan). Returns, for each vertex added (numbered from
// vertexCount on), the vertex it was split from. `faces` must run each directed edge at most once.
std::vector<int> splitFans(Polygons& faces, int vertexCount);

// Closes by one polygon each boundary loop whose vertices `inside` all marks (vertices no
// boundary of the input is near); the loops of the input's own boundaries stay open. `faces`:
// as splitFans leaves them, so that every loop is simple.
void closeHoles(Polygons& faces, const std::vector<char>& inside);

// Whether every edge of `mesh` joins at most two faces that run it opposite ways, and the faces
// around every vertex are one fan (a disk, or a half disk on a boundary).
bool isManifold(const mesh::PolygonMesh& mesh);

}  // namespace subdfit::simplify::remesh
