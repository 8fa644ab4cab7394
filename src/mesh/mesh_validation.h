#pragma once
// The invariants every PolygonMesh leaving the loader satisfies, checked once in one place.
#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Throws subdfit::Error "sourcePath: problem" unless the mesh has at least one face, every face
// has at least 3 vertices, faceIndices has sum(faceSizes) entries all naming existing vertices,
// every position is finite, and every tag names an existing vertex or face.
void validateMesh(const PolygonMesh& mesh);

}  // namespace subdfit::mesh
