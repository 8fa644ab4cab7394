#pragma once
// Workgroups that cover `count` invocations, `size` to a group.
#include <glad/gl.h>

namespace subdfit::gl {

inline GLuint groupsOf(int count, int size) { return GLuint((count + size - 1) / size); }

}  // namespace subdfit::gl
