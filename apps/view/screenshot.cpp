#include "screenshot.h"

#include <vector>

#include <glad/gl.h>
#include <glm/vec4.hpp>

#include "io/image_io.h"

namespace subdfit::view {

void writeScreenshot(const std::filesystem::path& path, int width, int height) {
    std::vector<glm::vec4> pixels(size_t(width) * size_t(height));
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_FLOAT, pixels.data());
    io::writeImage(path, pixels, width, height);
}

}  // namespace subdfit::view
