#pragma once
// glTF 2.0 reference meshes (.gltf with external or embedded buffers, and .glb), including
// KHR_draco_mesh_compression primitives.
#include <filesystem>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// All triangle primitives (modes TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN) of all nodes of the
// default scene (the first scene when none is named; every mesh once when there are no
// scenes), with node transforms applied, merged into one triangle mesh. Point and line
// primitives are skipped. Throws subdfit::Error naming the file for malformed JSON or GLB,
// out-of-bounds accessors, bad indices, non-finite positions, unsupported required extensions,
// or a file without triangles. With MeshContent::WithAppearance also TEXCOORD_0, COLOR_0, the
// materials and their images (gltf_materials.h).
PolygonMesh readGltf(const std::filesystem::path& path, MeshContent content = MeshContent::Geometry);

}  // namespace subdfit::mesh
