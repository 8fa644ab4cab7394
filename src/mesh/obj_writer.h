#pragma once
// Writes a cage back as OBJ with OpenSubdiv's `t` tags, so that readObj(writeObj(m)) gives m.
#include <filesystem>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Writes `v` lines (shortest text that reads back as the same float), 1-based `f` lines, and
// the `t` tags (creases, corners, holes, the rule tags the source named, passthrough lines
// verbatim). Atomic: the file appears complete or not at all (a temporary file beside it is
// renamed over it). Throws subdfit::Error "path: problem" on any failure, leaving no temporary
// file behind.
void writeObj(const std::filesystem::path& path, const PolygonMesh& mesh);

}  // namespace subdfit::mesh
