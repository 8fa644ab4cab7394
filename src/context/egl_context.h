#pragma once
#include "context/gl_context.h"

namespace subdfit::context {

// Headless EGL: the first device that gives a 4.5 core context (a GPU driver first, then
// Mesa's surfaceless platform, which also works on CPU-only machines).
std::unique_ptr<GlContext> createEglContext();

}  // namespace subdfit::context
