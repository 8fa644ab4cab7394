// g̃ = (I + λL)⁻¹ g by damped Jacobi sweeps (jacobi.glsl): a small group's all in one work group,
// a larger one's one sweep per dispatch.
#include "bindings.h"
#include "jacobi.glsl"

// g and the iterate a sweep starts from, read as buffer textures.
layout(binding = SUBDFIT_UNIT_JACOBI_GRADIENT) uniform samplerBuffer gradient;
layout(binding = SUBDFIT_UNIT_JACOBI_IN) uniform samplerBuffer smoothIn;
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer SmoothOut { float smoothOut[]; };

#ifdef SUBDFIT_PRECONDITION_ONE_GROUP
layout(local_size_x = 256) in;

uniform int uIterations;

vec4 gradientOf(int v) { return texelFetch(gradient, v); }

void main() {
    const int floats = SUBDFIT_CHANNELS * uVertexCount;
    for (int i = int(gl_LocalInvocationIndex); i < floats; i += 256)
        iterate[0][i] = texelFetch(gradient, i / SUBDFIT_CHANNELS)[i % SUBDFIT_CHANNELS];
    barrier();
    const int result = sweepInSharedMemory(uIterations);
    for (int i = int(gl_LocalInvocationIndex); i < floats; i += 256) smoothOut[i] = iterate[result][i];
}
#else
layout(local_size_x = 128) in;

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
    int begin = texelFetch(adjacencyOffsets, v).x, end = texelFetch(adjacencyOffsets, v + 1).x;
    vec4 neighbourSum = vec4(0.0);
    for (int k = begin; k < end; ++k) neighbourSum += texelFetch(smoothIn, texelFetch(adjacencyIndices, k).x);
    float scale = 1.0 / (1.0 + uLambda * float(end - begin));
    vec4 smoothed = jacobi(texelFetch(smoothIn, v), texelFetch(gradient, v), neighbourSum, scale);
    for (int c = 0; c < SUBDFIT_CHANNELS; ++c) smoothOut[SUBDFIT_CHANNELS * v + c] = smoothed[c];
}
#endif
