#include "render/render_target.h"

#include "bindings.h"
#include "util/error.h"

namespace subdfit::render {

RenderTarget::RenderTarget(int width, int height, TargetLayout layout)
    : width_(width),
      height_(height),
      layout_(layout),
      color_(GL_RGBA32F, width, height),
      faceId_(layout.faceInAlpha ? gl::Texture() : gl::Texture(GL_R32I, width, height)),
      patchUv_(layout.patchUv ? gl::Texture(GL_RG32F, width, height) : gl::Texture()),
      depth_(GL_DEPTH_COMPONENT32F, width, height) {
    framebuffer_.attach(GL_COLOR_ATTACHMENT0 + SUBDFIT_ATTACHMENT_COLOR, color_);
    if (!layout.faceInAlpha) framebuffer_.attach(GL_COLOR_ATTACHMENT0 + SUBDFIT_ATTACHMENT_FACE_ID, faceId_);
    if (layout.patchUv) framebuffer_.attach(GL_COLOR_ATTACHMENT0 + SUBDFIT_ATTACHMENT_PATCH_UV, patchUv_);
    framebuffer_.attach(GL_DEPTH_ATTACHMENT, depth_);
    const auto attachedIf = [](bool attached, GLenum attachment) { return attached ? attachment : GLenum(GL_NONE); };
    framebuffer_.drawBuffers({GL_COLOR_ATTACHMENT0, attachedIf(!layout.faceInAlpha, GL_COLOR_ATTACHMENT1),
                              attachedIf(layout.patchUv, GL_COLOR_ATTACHMENT2)});
    if (!framebuffer_.complete())
        throw Error("render target " + std::to_string(width) + "x" + std::to_string(height) +
                    " is not complete on this GL implementation");
}

void RenderTarget::bindAndClear() const {
    framebuffer_.bind();
    glViewport(0, 0, width_, height_);
    const float black[] = {0, 0, 0, 0};
    const float blackNoFace[] = {0, 0, 0, -1};
    const int noFace[] = {-1, -1, -1, -1};
    const float one = 1.0f;
    glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, SUBDFIT_ATTACHMENT_COLOR,
                              layout_.faceInAlpha ? blackNoFace : black);
    if (!layout_.faceInAlpha)
        glClearNamedFramebufferiv(framebuffer_.id(), GL_COLOR, SUBDFIT_ATTACHMENT_FACE_ID, noFace);
    if (layout_.patchUv) glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, SUBDFIT_ATTACHMENT_PATCH_UV, black);
    glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &one);
}

std::vector<glm::vec4> RenderTarget::readColorAttachment() const {
    std::vector<glm::vec4> pixels(size_t(width_) * height_);
    glGetTextureImage(color_.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec4)), pixels.data());
    return pixels;
}

std::vector<glm::vec4> RenderTarget::readColor() const {
    auto pixels = readColorAttachment();
    if (layout_.faceInAlpha)
        for (auto& p : pixels) p.a = p.a >= 0.0f ? 1.0f : 0.0f;
    return pixels;
}

const gl::Texture& RenderTarget::faceId() const {
    SUBDFIT_CHECK(!layout_.faceInAlpha);
    return faceId_;
}

std::vector<int> RenderTarget::readFaceId() const {
    std::vector<int> pixels(size_t(width_) * height_);
    if (layout_.faceInAlpha) {
        const auto colors = readColorAttachment();
        for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = int(colors[i].a);
        return pixels;
    }
    glGetTextureImage(faceId_.id(), 0, GL_RED_INTEGER, GL_INT, GLsizei(pixels.size() * sizeof(int)), pixels.data());
    return pixels;
}

const gl::Texture& RenderTarget::patchUv() const {
    SUBDFIT_CHECK(layout_.patchUv);
    return patchUv_;
}

std::vector<glm::vec2> RenderTarget::readPatchUv() const {
    SUBDFIT_CHECK(layout_.patchUv);
    std::vector<glm::vec2> pixels(size_t(width_) * height_);
    glGetTextureImage(patchUv_.id(), 0, GL_RG, GL_FLOAT, GLsizei(pixels.size() * sizeof(glm::vec2)), pixels.data());
    return pixels;
}

std::vector<float> RenderTarget::readDepth() const {
    std::vector<float> pixels(size_t(width_) * height_);
    glGetTextureImage(depth_.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(pixels.size() * sizeof(float)),
                      pixels.data());
    return pixels;
}

}  // namespace subdfit::render
