#pragma once
#include "gl/gl_handle.h"

namespace subdfit::gl {

// A 2D texture or 2D array with immutable storage and nearest filtering (render targets and
// per-pixel data are fetched, never filtered).
class Texture {
public:
    Texture() = default;
    Texture(GLenum internalFormat, int width, int height, int layers = 0);

    GLuint id() const { return handle_.id(); }
    int width() const { return width_; }
    int height() const { return height_; }
    int layers() const { return layers_; }
    GLenum format() const { return format_; }

private:
    GlHandle<TextureTraits> handle_;
    int width_ = 0, height_ = 0, layers_ = 0;
    GLenum format_ = 0;
};

}  // namespace subdfit::gl
