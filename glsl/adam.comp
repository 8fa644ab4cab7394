// Adam on one parameter group (adam.glsl), one thread per parameter.
// SUBDFIT_ADAM_SHARED_MOMENT: one second moment for the group (see shared_moment.comp) scales
// the step; each parameter's own second moment is still kept, for the noise gate.
#include "bindings.h"
#include "adam.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) buffer Theta { float theta[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) readonly buffer Gradient { float gradient[]; };
#ifdef SUBDFIT_ADAM_SHARED_MOMENT
layout(std430, binding = SUBDFIT_SSBO_GROUP_MOMENT2) readonly buffer GroupMoment2 { float groupMoment2; };
#endif

uniform uint uCount;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uCount) return;
#ifdef SUBDFIT_ADAM_SHARED_MOMENT
    float groupV = groupMoment2;  // updated for the whole group by shared_moment.comp
#else
    float groupV = -1.0;
#endif
    theta[i] -= adamStep(i, gradient[i], groupV);
}
