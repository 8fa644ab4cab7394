#include "gl/vertex_array.h"

namespace subdfit::gl {

VertexArray::VertexArray() {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    handle_ = GlHandle<VertexArrayTraits>(id);
}

void VertexArray::attribute(GLuint index, const Buffer& buffer, int components) {
    glVertexArrayVertexBuffer(id(), index, buffer.id(), 0, GLsizei(components * sizeof(float)));
    glEnableVertexArrayAttrib(id(), index);
    glVertexArrayAttribFormat(id(), index, components, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(id(), index, index);
}

void VertexArray::elements(const Buffer& indices) const { glVertexArrayElementBuffer(id(), indices.id()); }

void VertexArray::recordAttribute(GLuint index, int components, GLuint offset, bool integer) {
    glEnableVertexArrayAttrib(id(), index);
    if (integer) glVertexArrayAttribIFormat(id(), index, 1, GL_INT, offset);
    else glVertexArrayAttribFormat(id(), index, components, GL_FLOAT, GL_FALSE, offset);
    glVertexArrayAttribBinding(id(), index, kRecordBinding);
}

void VertexArray::records(const Buffer& buffer, GLsizei stride) const {
    glVertexArrayVertexBuffer(id(), kRecordBinding, buffer.id(), 0, stride);
}

}  // namespace subdfit::gl
