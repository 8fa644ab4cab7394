#pragma once
// Draco-compressed meshes: `.drc` files, and the KHR_draco_mesh_compression payloads inside
// glTF (the Debian tinygltf is built without Draco, so gltf_reader decodes them here).
#include <cstddef>
#include <filesystem>
#include <string>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Decodes a Draco triangle mesh: one vertex per Draco point, one triangle per Draco face.
// Positions come from the attribute with `positionUniqueId` (the id glTF's extension names),
// or from the POSITION attribute when it is negative. Throws subdfit::Error naming
// `pathForErrors` for corrupt data, point clouds and missing or non-3D positions.
PolygonMesh decodeDracoMesh(const char* data, size_t size, const std::string& pathForErrors,
                            int positionUniqueId = -1);

// Reads a `.drc` file (a mesh; a point cloud is an error).
PolygonMesh readDraco(const std::filesystem::path& path);

}  // namespace subdfit::mesh
