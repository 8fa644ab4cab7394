#pragma once
// An immutable-storage GL buffer (DSA), mostly used as an SSBO holding parameters,
// moments, gradients or tables. Contents can be rewritten; the size cannot.
#include <span>
#include <vector>

#include "gl/gl_handle.h"
#include "util/error.h"

namespace subdfit::gl {

// A storage buffer past this GL's largest block (Buffer::bindStorage): what needs it cannot be
// drawn here, which a search may weigh as such.
class StorageBlockExceeded : public Error {
public:
    using Error::Error;
};

class Buffer {
public:
    Buffer() = default;
    // `bytes` of storage, zero-filled when `data` is null.
    Buffer(GLsizeiptr bytes, const void* data = nullptr);

    template <class T>
    static Buffer fromSpan(std::span<const T> values) {
        // GL rejects zero-sized storage; keep one element so binding an empty table stays legal.
        return values.empty() ? Buffer(sizeof(T)) : Buffer(values.size_bytes(), values.data());
    }
    template <class T>
    static Buffer fromVector(const std::vector<T>& values) {
        return fromSpan(std::span<const T>(values));
    }

    GLuint id() const { return handle_.id(); }
    GLsizeiptr bytes() const { return bytes_; }

    void bindStorage(GLuint binding) const;  // GL_SHADER_STORAGE_BUFFER indexed binding
    void upload(const void* data, GLsizeiptr bytes, GLintptr offset = 0);
    void download(void* data, GLsizeiptr bytes, GLintptr offset = 0) const;
    void clearToZero();
    void copyFrom(const Buffer& source);

    template <class T>
    std::vector<T> read() const {
        std::vector<T> values(bytes_ / sizeof(T));
        download(values.data(), GLsizeiptr(values.size() * sizeof(T)));
        return values;
    }

private:
    GlHandle<BufferTraits> handle_;
    GLsizeiptr bytes_ = 0;
};

}  // namespace subdfit::gl
