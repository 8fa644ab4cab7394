#include "export/engine/surface_error.h"

#include "surface/tessellation.h"

namespace subdfit::exporter {

mesh::PolygonMesh triangleMeshOf(const GltfMesh& mesh) { return surface::triangleMesh(mesh.positions, mesh.indices); }

}  // namespace subdfit::exporter
