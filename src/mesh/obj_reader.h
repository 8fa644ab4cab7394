#pragma once
// Wavefront OBJ with OpenSubdiv's `t` tags: the format of cages and of OpenSubdiv's
// regression shapes.
#include <filesystem>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Reads `v` and `f` lines (`f` entries v, v/vt, v//vn, v/vt/vn; negative indices count back
// from the last vertex read) and `t` tags; normals, groups and other statements are ignored.
// With MeshContent::WithAppearance also `vt`, `usemtl` and `mtllib` (obj_materials.h): vertices
// are split where their faces use different texture coordinates, and the tags dropped. Throws
// subdfit::Error "path: line N: problem" for malformed input, indices out of range, non-finite
// coordinates, or a file without faces.
PolygonMesh readObj(const std::filesystem::path& path, MeshContent content = MeshContent::Geometry);

}  // namespace subdfit::mesh
