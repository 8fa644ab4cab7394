#pragma once
// A vertex array object (DSA), move-only. Core-profile draws need one bound even when the vertex
// shader reads no attributes (the patch and full-screen passes fetch from SSBOs or gl_VertexID).
#include "gl/buffer.h"
#include "gl/gl_handle.h"

namespace subdfit::gl {

class VertexArray {
public:
    VertexArray();

    GLuint id() const { return handle_.id(); }
    // Attribute `index` reads `components` tightly packed floats per vertex from `buffer`.
    void attribute(GLuint index, const Buffer& buffer, int components);
    void elements(const Buffer& indices) const;
    // Interleaved records instead (not mixed with attribute()): attribute `index` reads
    // `components` floats, or one int, `offset` bytes into each record of the buffer that
    // records() binds, `stride` bytes apart.
    void recordAttribute(GLuint index, int components, GLuint offset, bool integer = false);
    void records(const Buffer& buffer, GLsizei stride) const;
    void bind() const { glBindVertexArray(id()); }

private:
    static constexpr GLuint kRecordBinding = 0;
    GlHandle<VertexArrayTraits> handle_;
};

}  // namespace subdfit::gl
