#pragma once
#include <filesystem>

namespace subdfit::view {

// Writes the default framebuffer's back buffer (what the next swap will show) as an image,
// atomically (io::writeImage). Throws subdfit::Error naming the file.
void writeScreenshot(const std::filesystem::path& path, int width, int height);

}  // namespace subdfit::view
