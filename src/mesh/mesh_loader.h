#pragma once
// The one entry point for reading a mesh from disk, whatever its format.
#include <filesystem>

#include "mesh/mesh_geometry.h"    // triangulated(), vertexNormals(): callers of loadMesh use them
#include "mesh/mesh_validation.h"  // validateMesh()
#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Reads .obj (with OpenSubdiv tags), .gltf, .glb or .drc, chosen by the extension (any case),
// and checks the result with validateMesh. Throws subdfit::Error "path: problem" for any
// other extension and for every input problem.
PolygonMesh loadMesh(const std::filesystem::path& path);

// loadMesh for a reference: also its appearance (texture coordinates, colours, materials and
// their images) where the file has one.
PolygonMesh loadReference(const std::filesystem::path& path);

}  // namespace subdfit::mesh
