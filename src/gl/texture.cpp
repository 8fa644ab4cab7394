#include "gl/texture.h"

namespace subdfit::gl {

Texture::Texture(GLenum internalFormat, int width, int height, int layers)
    : width_(width), height_(height), layers_(layers), format_(internalFormat) {
    GLuint id = 0;
    glCreateTextures(layers > 0 ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D, 1, &id);
    handle_ = GlHandle<TextureTraits>(id);
    if (layers > 0)
        glTextureStorage3D(id, 1, internalFormat, width, height, layers);
    else
        glTextureStorage2D(id, 1, internalFormat, width, height);
    glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(id, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(id, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

}  // namespace subdfit::gl
