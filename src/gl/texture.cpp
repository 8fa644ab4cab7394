#include "gl/texture.h"

#include <algorithm>
#include <string>

#include "util/error.h"

namespace subdfit::gl {

Texture::Texture(GLenum internalFormat, int width, int height, int layers)
    : width_(width), height_(height), layers_(layers), format_(internalFormat) {
    GLuint id = 0;
    glCreateTextures(layers > 0 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D, 1, &id);
    handle_ = GlHandle<TextureTraits>(id);
    if (layers > 0) glTextureStorage3D(id, 1, internalFormat, width, height, layers);
    else glTextureStorage2D(id, 1, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void Texture::bindImage(GLuint unit, GLenum access) const {
    glBindImageTexture(unit, id(), 0, layers_ > 0 ? GL_TRUE : GL_FALSE, 0, access, format_);
}

Texture Texture::fromImage(const std::uint8_t* rgba, int width, int height, bool srgb) {
    Texture t;
    t.width_ = width;
    t.height_ = height;
    t.format_ = srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8;
    int levels = 1;
    while ((std::max(width, height) >> levels) > 0) ++levels;
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &id);
    t.handle_ = GlHandle<TextureTraits>(id);
    glTextureStorage2D(id, levels, t.format_, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(id, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
    glGenerateTextureMipmap(id);
    return t;
}

namespace {

GLsizeiptr texelBytesOf(GLenum format) {
    switch (format) {
        case GL_R32F:
        case GL_R32I: return 4;
        case GL_RG32F:
        case GL_RG32I:
        case GL_RG32UI: return 8;
        case GL_RGB32F: return 12;
        case GL_RGBA32F:
        case GL_RGBA32I:
        case GL_RGBA32UI: return 16;
        default: throw Error("no buffer texture of format " + std::to_string(format));
    }
}

}  // namespace

BufferTexture::BufferTexture(const Buffer& buffer, GLenum format) {
    const GLsizeiptr texelBytes = texelBytesOf(format);
    GLint most = 0;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &most);
    if (buffer.bytes() / texelBytes > most)
        throw Error("a buffer of " + std::to_string(buffer.bytes() / texelBytes) +
                    " texels is past this GL's largest buffer texture (" + std::to_string(most) + ")");
    GLuint id = 0;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &id);
    handle_ = GlHandle<TextureTraits>(id);
    glTextureBuffer(id, format, buffer.id());
}

BufferTexture BufferTexture::ofFloats(const Buffer& buffer, int channels) {
    constexpr GLenum kFormats[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
    return BufferTexture(buffer, kFormats[std::clamp(channels, 1, 4) - 1]);
}

Sampler::Sampler(GLenum wrapS, GLenum wrapT, bool nearest) {
    GLuint id = 0;
    glCreateSamplers(1, &id);
    handle_ = GlHandle<SamplerTraits>(id);
    glSamplerParameteri(id, GL_TEXTURE_WRAP_S, GLint(wrapS));
    glSamplerParameteri(id, GL_TEXTURE_WRAP_T, GLint(wrapT));
    glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR);
    glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, nearest ? GL_NEAREST : GL_LINEAR);
}

}  // namespace subdfit::gl
