#pragma once
// A test mesh as a glTF split at every seam has it: each triangle with three vertices of its own
// (so each side of every edge is shaded with its own face's normal).
#include "mesh/mesh_geometry.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::testing {

inline mesh::PolygonMesh splitTriangles(const mesh::PolygonMesh& m) {
    const mesh::PolygonMesh t = mesh::triangulated(m);
    mesh::PolygonMesh out;
    for (int i : t.faceIndices) {
        out.faceIndices.push_back(int(out.positions.size()));
        out.positions.push_back(t.positions[size_t(i)]);
    }
    out.faceSizes.assign(t.faceSizes.size(), 3);
    return out;
}

}  // namespace subdfit::testing
