// R for the triangle soup: no vertex attributes; corner gl_VertexID of triangle gl_VertexID / 3
// is fetched from the position SSBO (θ, θ+ or θ−) and the triangle's flat colour from the colour
// SSBO, so one glDrawArrays(GL_TRIANGLES, 0, 3N) renders any of the three parameter states.
#include "soup_bindings.h"

layout(std430, binding = SUBDFIT_SOUP_SSBO_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, binding = SUBDFIT_SOUP_SSBO_COLORS) readonly buffer Colors { float colors[]; };

flat out vec3 vColor;

void main() {
    int p = 3 * gl_VertexID;
    int c = 3 * (gl_VertexID / 3);
    gl_Position = vec4(positions[p], positions[p + 1], positions[p + 2], 1.0);
    vColor = vec3(colors[c], colors[c + 1], colors[c + 2]);
}
