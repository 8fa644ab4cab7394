// The cage's edges, read straight from the fitted control vertices θ (3 floats per vertex):
// drawn with an edge index buffer and no vertex attributes, so gl_VertexID is the vertex index.
#include "bindings.h"

layout(std430, binding = SUBDFIT_SSBO_THETA) readonly buffer Theta { float theta[]; };

uniform mat4 uViewProjection;

void main() {
    int v = gl_VertexID;
    gl_Position = uViewProjection * vec4(theta[3 * v], theta[3 * v + 1], theta[3 * v + 2], 1.0);
}
