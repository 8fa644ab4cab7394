#pragma once
#include "context/gl_context.h"
#include "gl/program_cache.h"

namespace subdfit::test {

// The program cache of the binary's shared context (created in gl_test_main.cpp).
gl::ProgramCache& programs();
// SUBDFIT_ATOMIC_FLOAT when the context has GL_NV_shader_atomic_float.
gl::Defines platformDefines();
// Fails the current test if GL recorded an error.
void expectNoGlError();

}  // namespace subdfit::test
