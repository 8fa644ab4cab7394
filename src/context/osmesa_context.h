#pragma once
#include "context/gl_context.h"

namespace subdfit::context {

// Kept out of every other translation unit: <GL/osmesa.h> drags in <GL/gl.h>, which clashes
// with glad's header.
std::unique_ptr<GlContext> createOsmesaContext();

}  // namespace subdfit::context
