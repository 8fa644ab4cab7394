#include "gl/framebuffer.h"

#include <vector>

namespace subdfit::gl {

Framebuffer::Framebuffer() {
    GLuint id = 0;
    glCreateFramebuffers(1, &id);
    handle_ = GlHandle<FramebufferTraits>(id);
}

void Framebuffer::attach(GLenum attachment, const Texture& texture) {
    glNamedFramebufferTexture(id(), attachment, texture.id(), 0);
}

void Framebuffer::drawBuffers(std::initializer_list<GLenum> attachments) {
    const std::vector<GLenum> buffers(attachments);
    glNamedFramebufferDrawBuffers(id(), GLsizei(buffers.size()), buffers.data());
}

bool Framebuffer::complete() const {
    return glCheckNamedFramebufferStatus(id(), GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

}  // namespace subdfit::gl
