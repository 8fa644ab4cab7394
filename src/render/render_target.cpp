#include "render/render_target.h"

#include "bindings.h"
#include "util/error.h"

namespace subdfit::render {

RenderTarget::RenderTarget(int width, int height, bool patchUv)
    : width_(width),
      height_(height),
      color_(GL_RGBA32F, width, height),
      faceId_(GL_R32I, width, height),
      patchUv_(patchUv ? gl::Texture(GL_RG32F, width, height) : gl::Texture()),
      depth_(GL_DEPTH_COMPONENT32F, width, height) {
    framebuffer_.attach(GL_COLOR_ATTACHMENT0 + SUBDFIT_ATTACHMENT_COLOR, color_);
    framebuffer_.attach(GL_COLOR_ATTACHMENT0 + SUBDFIT_ATTACHMENT_FACE_ID, faceId_);
    if (patchUv) framebuffer_.attach(GL_COLOR_ATTACHMENT0 + SUBDFIT_ATTACHMENT_PATCH_UV, patchUv_);
    framebuffer_.attach(GL_DEPTH_ATTACHMENT, depth_);
    framebuffer_.drawBuffers({GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, patchUv ? GL_COLOR_ATTACHMENT2 : GL_NONE});
    if (!framebuffer_.complete())
        throw Error("render target " + std::to_string(width) + "x" + std::to_string(height) +
                    " is not complete on this GL implementation");
}

void RenderTarget::bindAndClear() const {
    framebuffer_.bind();
    glViewport(0, 0, width_, height_);
    const float black[] = {0, 0, 0, 0};
    const int noFace[] = {-1, -1, -1, -1};
    const float one = 1.0f;
    glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, SUBDFIT_ATTACHMENT_COLOR, black);
    glClearNamedFramebufferiv(framebuffer_.id(), GL_COLOR, SUBDFIT_ATTACHMENT_FACE_ID, noFace);
    if (patchUv_.id() != 0) glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, SUBDFIT_ATTACHMENT_PATCH_UV, black);
    glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &one);
}

std::vector<glm::vec4> RenderTarget::readColor() const {
    std::vector<glm::vec4> pixels(size_t(width_) * height_);
    glGetTextureImage(color_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

std::vector<int> RenderTarget::readFaceId() const {
    std::vector<int> pixels(size_t(width_) * height_);
    glGetTextureImage(faceId_.id(), 0, GL_RED_INTEGER, GL_INT, GLsizei(pixels.size() * sizeof(int)), pixels.data());
    return pixels;
}

const gl::Texture& RenderTarget::patchUv() const {
    SUBDFIT_CHECK(patchUv_.id() != 0);
    return patchUv_;
}

std::vector<glm::vec2> RenderTarget::readPatchUv() const {
    SUBDFIT_CHECK(patchUv_.id() != 0);
    std::vector<glm::vec2> pixels(size_t(width_) * height_);
    glGetTextureImage(patchUv_.id(), 0, GL_RG, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec2)), pixels.data());
    return pixels;
}

std::vector<float> RenderTarget::readDepth() const {
    std::vector<float> pixels(size_t(width_) * height_);
    glGetTextureImage(depth_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)), pixels.data());
    return pixels;
}

}  // namespace subdfit::render
