#include "export/engine/surface_error.h"

namespace subdfit::exporter {

mesh::PolygonMesh triangleMeshOf(const GltfMesh& mesh) {
    mesh::PolygonMesh out;
    out.positions = mesh.positions;
    out.faceSizes.assign(mesh.triangleCount(), 3);
    out.faceIndices.assign(mesh.indices.begin(), mesh.indices.end());
    return out;
}

}  // namespace subdfit::exporter
