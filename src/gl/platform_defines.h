#pragma once
#include "gl/program.h"

namespace subdfit::gl {

// The defines every program gets from the current context's capabilities (today only
// SUBDFIT_ATOMIC_FLOAT where GL_NV_shader_atomic_float exists): the global defines of a
// run's ProgramCache. Requires a current context with GL loaded.
Defines platformDefines();

}  // namespace subdfit::gl
