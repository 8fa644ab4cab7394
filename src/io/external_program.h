#pragma once
// Other programs subdfit runs (the gltfpack baseline): found on PATH, run with their output
// discarded, waited for.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace subdfit::io {

// The first executable `name` on PATH, if any.
std::optional<std::filesystem::path> findProgram(const std::string& name);

// Runs `program` with `arguments` (no shell), stdout and stderr to /dev/null; returns its exit
// status (128 + signal when killed). Throws subdfit::Error when it cannot be started.
int runProgram(const std::filesystem::path& program, const std::vector<std::string>& arguments);

}  // namespace subdfit::io
