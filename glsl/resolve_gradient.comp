// The fixed-point sums G accumulated (fixed_point.glsl) as the float gradient the
// preconditioner and Adam read; the sums are then cleared by the caller.
#include "bindings.h"
#include "fixed_point.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SUM) readonly buffer Sum { uint sum[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT) writeonly buffer Gradient { float gradient[]; };

uniform uint uCount;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i < uCount) gradient[i] = fromFixed(sum[2u * i], sum[2u * i + 1u]);
}
