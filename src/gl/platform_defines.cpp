#include "gl/platform_defines.h"

namespace subdfit::gl {

Defines platformDefines() { return GLAD_GL_NV_shader_atomic_float ? Defines{{"SUBDFIT_ATOMIC_FLOAT", ""}} : Defines{}; }

}  // namespace subdfit::gl
