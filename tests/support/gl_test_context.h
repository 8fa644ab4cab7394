#pragma once
#include "context/gl_context.h"
#include "gl/program_cache.h"

namespace subdfit::test {

// The binary's shared context, and its program cache (created in gl_test_main.cpp).
const context::GlContext& glContext();
gl::ProgramCache& programs();
// SUBDFIT_ATOMIC_FLOAT when the context has GL_NV_shader_atomic_float.
gl::Defines platformDefines();
// Makes the shared context current before every test (gl_test_main.cpp calls it once).
void installSharedContextListener();
// Fails the current test if GL recorded an error.
void expectNoGlError();

}  // namespace subdfit::test
