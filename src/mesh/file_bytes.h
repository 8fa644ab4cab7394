#pragma once
// Whole-file reads for the mesh readers: one buffer, parsed in place, so that a large OBJ is
// not read token by token through iostreams.
#include <filesystem>
#include <string>

namespace subdfit::mesh {

// The file's bytes. Throws subdfit::Error "path: cannot read ..." when it is missing, a
// folder, or unreadable.
std::string readFileBytes(const std::filesystem::path& path);

}  // namespace subdfit::mesh
