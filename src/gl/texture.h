#pragma once
#include <cstdint>

#include "gl/buffer.h"
#include "gl/gl_handle.h"

namespace subdfit::gl {

// A 2D texture or 2D array with immutable storage and nearest filtering (render targets and
// per-pixel data are fetched, never filtered).
class Texture {
public:
    Texture() = default;
    Texture(GLenum internalFormat, int width, int height, int layers = 0);

    // An 8-bit RGBA image (rows top first, as image files store them, so that texture coordinate
    // v = 0 is its top row, as glTF's is) with a full mip chain, for filtered sampling through a
    // Sampler. `srgb`: stored as sRGB, so that fetches return linear values.
    static Texture fromImage(const std::uint8_t* rgba, int width, int height, bool srgb);

    GLuint id() const { return handle_.id(); }
    // Binds level 0, all its layers, to image `unit` for imageLoad in its own format.
    void bindImageForReading(GLuint unit) const { bindImage(unit, GL_READ_ONLY); }
    void bindImage(GLuint unit, GLenum access) const;  // GL_READ_ONLY, GL_WRITE_ONLY or GL_READ_WRITE
    int width() const { return width_; }
    int height() const { return height_; }
    int layers() const { return layers_; }
    GLenum format() const { return format_; }

private:
    GlHandle<TextureTraits> handle_;
    int width_ = 0, height_ = 0, layers_ = 0;
    GLenum format_ = 0;
};

// A buffer read as a texture (GL_TEXTURE_BUFFER): `texelFetch` of a samplerBuffer gathers a
// texel of `format` (GL_RGB32F: a point of three floats) in one fetch, where an SSBO read is
// one load per float. It views the buffer's storage; the buffer must outlive it.
class BufferTexture {
public:
    BufferTexture() = default;
    BufferTexture(const Buffer& buffer, GLenum format);
    // `channels` (1-4) 32-bit floats per texel.
    static BufferTexture ofFloats(const Buffer& buffer, int channels);
    GLuint id() const { return handle_.id(); }
    void bind(GLuint unit) const { glBindTextureUnit(unit, id()); }

private:
    GlHandle<TextureTraits> handle_;
};

// Sampler state (DSA), move-only: how a texture unit filters and wraps.
class Sampler {
public:
    Sampler(GLenum wrapS, GLenum wrapT, bool nearest);
    GLuint id() const { return handle_.id(); }
    void bind(GLuint unit) const { glBindSampler(unit, id()); }

private:
    GlHandle<SamplerTraits> handle_;
};

}  // namespace subdfit::gl
