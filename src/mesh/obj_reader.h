#pragma once
// Wavefront OBJ with OpenSubdiv's `t` tags: the format of cages and of OpenSubdiv's
// regression shapes.
#include <filesystem>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Reads `v` and `f` lines (`f` entries v, v/vt, v//vn, v/vt/vn; negative indices count back
// from the last vertex read) and `t` tags; texture coordinates, normals, groups, materials and
// other statements are ignored. Throws subdfit::Error "path: line N: problem" for malformed
// input, indices out of range, non-finite coordinates, or a file without faces.
PolygonMesh readObj(const std::filesystem::path& path);

}  // namespace subdfit::mesh
