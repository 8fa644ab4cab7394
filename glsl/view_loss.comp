// One view's loss, Σ_p |c_p − t_p|² over its RGB (c_p filtered as the targets were,
// supersampling.glsl), summed per work group: the caller adds the groups' sums in double. What
// a choice between candidates reads, without reading their images back.
#include "bindings.h"
#include "supersampling.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = SUBDFIT_IMAGE_TARGET, rgba32f) readonly uniform image2DArray targets;
layout(std430, binding = SUBDFIT_SSBO_VIEW_LOSS) writeonly buffer GroupSums { float groupSum[]; };

uniform int uResolution;
uniform int uLayer;

shared float partial[256];

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    uint lane = gl_LocalInvocationIndex;
    float error = 0.0;
    if (all(lessThan(pixel, ivec2(uResolution)))) {
        vec3 d = filteredPixel(pixel).rgb - imageLoad(targets, ivec3(pixel, uLayer)).rgb;
        error = dot(d, d);
    }
    partial[lane] = error;
    barrier();
    for (uint stride = 128u; stride > 0u; stride >>= 1u) {
        if (lane < stride) partial[lane] += partial[lane + stride];
        barrier();
    }
    if (lane == 0u) groupSum[gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x] = partial[0];
}
