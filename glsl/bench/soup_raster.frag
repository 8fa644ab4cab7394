// Flat colour plus the triangle id. For a non-indexed GL_TRIANGLES draw gl_PrimitiveID is the
// triangle index; soup.cpp checks that on llvmpipe (every covered pixel's colour must be the
// colour of the triangle its id names) before it trusts the id buffer.
#include "soup_bindings.h"

flat in vec3 vColor;

layout(location = SUBDFIT_SOUP_ATTACHMENT_COLOR) out vec4 outColor;
layout(location = SUBDFIT_SOUP_ATTACHMENT_TRIANGLE) out int outTriangle;

void main() {
    outColor = vec4(vColor, 1.0);
    outTriangle = gl_PrimitiveID;
}
