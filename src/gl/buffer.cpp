#include "gl/buffer.h"

#include "util/error.h"

namespace subdfit::gl {

Buffer::Buffer(GLsizeiptr bytes, const void* data) : bytes_(bytes) {
    SUBDFIT_CHECK(bytes > 0);
    GLuint id = 0;
    glCreateBuffers(1, &id);
    handle_ = GlHandle<BufferTraits>(id);
    glNamedBufferStorage(id, bytes, data, GL_DYNAMIC_STORAGE_BIT);
    if (!data) clearToZero();
}

void Buffer::bindStorage(GLuint binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id()); }

void Buffer::upload(const void* data, GLsizeiptr bytes, GLintptr offset) {
    SUBDFIT_CHECK(offset + bytes <= bytes_);
    glNamedBufferSubData(id(), offset, bytes, data);
}

void Buffer::download(void* data, GLsizeiptr bytes, GLintptr offset) const {
    SUBDFIT_CHECK(offset + bytes <= bytes_);
    glGetNamedBufferSubData(id(), offset, bytes, data);
}

void Buffer::clearToZero() { glClearNamedBufferData(id(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, nullptr); }

void Buffer::copyFrom(const Buffer& source) {
    SUBDFIT_CHECK(source.bytes_ == bytes_);
    glCopyNamedBufferSubData(source.id(), id(), 0, 0, bytes_);
}

}  // namespace subdfit::gl
