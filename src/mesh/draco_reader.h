#pragma once
// Draco-compressed meshes: `.drc` files, and the KHR_draco_mesh_compression payloads inside
// glTF (the Debian tinygltf is built without Draco, so gltf_reader decodes them here).
#include <cstddef>
#include <filesystem>
#include <string>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// The Draco attributes glTF's extension names by unique id (-1: position from the POSITION
// attribute; texture coordinates, colours and normals not read).
struct DracoAttributeIds {
    int position = -1, texCoord = -1, color = -1, normal = -1;
};

// Decodes a Draco triangle mesh: one vertex per Draco point, one triangle per Draco face, with
// the texture coordinates (mesh.uvs), colours (mesh.colors) and normals (mesh.normals, as
// stored: not normalised) `ids` names. Throws
// subdfit::Error naming `pathForErrors` for corrupt data, point clouds, missing or non-3D
// positions and missing or malformed texture coordinates or colours.
PolygonMesh decodeDracoMesh(const char* data, size_t size, const std::string& pathForErrors,
                            const DracoAttributeIds& ids = {});

// Reads a `.drc` file (a mesh; a point cloud is an error).
PolygonMesh readDraco(const std::filesystem::path& path);

}  // namespace subdfit::mesh
