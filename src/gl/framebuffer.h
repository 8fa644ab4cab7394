#pragma once
// A framebuffer object (DSA), move-only, with textures attached by the caller.
#include <initializer_list>

#include "gl/gl_handle.h"
#include "gl/texture.h"

namespace subdfit::gl {

class Framebuffer {
public:
    Framebuffer();

    GLuint id() const { return handle_.id(); }
    void attach(GLenum attachment, const Texture& texture);
    // The colour attachments fragment outputs 0, 1, ... write to.
    void drawBuffers(std::initializer_list<GLenum> attachments);
    bool complete() const;
    void bind() const { glBindFramebuffer(GL_FRAMEBUFFER, id()); }

private:
    GlHandle<FramebufferTraits> handle_;
};

}  // namespace subdfit::gl
