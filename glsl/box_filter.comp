// The mean of each uFactor × uFactor block of a supersampled render: the anti-aliased image a
// viewer shows (scene::TargetSet). Only this comes back to the CPU, a uFactor²-th of the samples.
#include "bindings.h"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = SUBDFIT_UNIT_SUPERSAMPLED) uniform sampler2D supersampled;
layout(std430, binding = SUBDFIT_SSBO_FILTERED) writeonly buffer Filtered { vec4 filtered[]; };

uniform int uResolution;
uniform int uFactor;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(uResolution)))) return;
    float weight = 1.0 / float(uFactor * uFactor);
    precise vec4 sum = vec4(0.0);
    for (int j = 0; j < uFactor; ++j)
        for (int i = 0; i < uFactor; ++i) sum += weight * texelFetch(supersampled, pixel * uFactor + ivec2(i, j), 0);
    filtered[pixel.y * uResolution + pixel.x] = sum;
}
