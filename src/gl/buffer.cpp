#include "gl/buffer.h"

#include <string>

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

void Buffer::bindStorage(GLuint binding) const {
    // A shader reads no further into a storage buffer than this GL's largest block: past it,
    // llvmpipe drops what it reads and writes, silently (a surface drawn wrong).
    static thread_local GLint64 most = 0;
    if (most == 0) glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &most);
    if (bytes_ > most)
        throw StorageBlockExceeded("a storage buffer of " + std::to_string(bytes_) +
                                   " bytes is past this GL's largest storage block (" + std::to_string(most) +
                                   " bytes): ask for fewer faces, map cells or segments");
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id());
}

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
