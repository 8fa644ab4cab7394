#pragma once
// How the LOD chain and the density from an error bound measure a decoded surface against
// another: area-uniform samples on each, the exact distance to the other, both ways
// (geometry/surface_distance.h), on the meshes' positions and triangles.
#include "export/gltf_mesh.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::exporter {

// Samples a side: enough that the mean is steady to a few per cent on the meshes decode writes.
inline constexpr int kErrorSamples = 100000;

// The mesh's positions and triangles, as geometry/ measures them.
mesh::PolygonMesh triangleMeshOf(const GltfMesh& mesh);

}  // namespace subdfit::exporter
