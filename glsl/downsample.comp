// A supersampled render filtered down to its resolution (supersampling.glsl), into a layer of
// an image array: a target set's view, or the scratch image a caller reads back.
#include "bindings.h"
#include "supersampling.glsl"

layout(local_size_x = 16, local_size_y = 16) in;

layout(binding = SUBDFIT_IMAGE_FILTERED, rgba32f) writeonly uniform image2DArray filtered;

uniform int uResolution;
uniform int uLayer;

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(pixel, ivec2(uResolution)))) return;
    imageStore(filtered, ivec3(pixel, uLayer), filteredPixel(pixel));
}
