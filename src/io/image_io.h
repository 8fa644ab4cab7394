#pragma once
#include <filesystem>
#include <glm/vec4.hpp>
#include <vector>

namespace subdfit::io {

// Writes an RGB image (rows bottom-up, as GL reads them) clamped to [0,1], 8-bit, format by
// extension (PNG, ...), atomically. Throws subdfit::Error naming the file on failure.
void writeImage(const std::filesystem::path& path, const std::vector<glm::vec4>& pixels, int width, int height);

}  // namespace subdfit::io
