// Large-steps style preconditioning of a gradient: g̃ = (I + λL)⁻¹ g with L the uniform graph
// Laplacian of the group's parameter graph (cage edges for vertices, the node grids for maps),
// by damped Jacobi iterations
//     g̃ ← (1 − ω) g̃ + ω (g + λ Σ_j∈N(i) g̃_j) / (1 + λ|N(i)|).
// Plain Jacobi (ω = 1) flips the sign of the checkerboard mode every sweep without shrinking
// it when λ is large; ω = 2/3 damps every high-frequency mode, which is the point here. It
// spreads each noisy per-parameter estimate over the neighbourhood, so the group moves smoothly
// and cannot tangle, while the low-frequency (shape) part of the gradient stays intact.
// SUBDFIT_CHANNELS: floats per graph node (3 for vertex positions, 1 for heights, 2 for normals).
#include "bindings.h"

#ifndef SUBDFIT_CHANNELS
#define SUBDFIT_CHANNELS 3
#endif

// g, the iterate a sweep starts from and the graph, read as buffer textures: a fetch gathers a
// node's channels, where an SSBO read is a load a float (one lane after another on llvmpipe).
layout(binding = SUBDFIT_UNIT_JACOBI_GRADIENT) uniform samplerBuffer gradient;
layout(binding = SUBDFIT_UNIT_JACOBI_IN) uniform samplerBuffer smoothIn;
layout(binding = SUBDFIT_UNIT_ADJACENCY_OFFSETS) uniform isamplerBuffer adjacencyOffsets;
layout(binding = SUBDFIT_UNIT_ADJACENCY_INDICES) uniform isamplerBuffer adjacencyIndices;
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer SmoothOut { float smoothOut[]; };

uniform int uVertexCount;
uniform float uLambda;

// One damped Jacobi update of node i's channels (the first SUBDFIT_CHANNELS of the four), from its
// neighbours' sum of the last iterate.
vec4 jacobi(vec4 current, vec4 g, vec4 neighbourSum, float scale) {
    const float omega = 2.0 / 3.0;
    return mix(current, (g + uLambda * neighbourSum) * scale, omega);
}

#ifdef SUBDFIT_PRECONDITION_ONE_GROUP
// Every sweep in one work group, the iterate in shared memory: a barrier between sweeps instead
// of a dispatch and a memory barrier each, whose fixed cost on a GPU outweighs a small group's
// sweeps. SUBDFIT_PRECONDITION_ONE_GROUP: floats the group holds at most (two iterates fit in
// the 32 KB of shared memory every GL 4.3 implementation has).
layout(local_size_x = 256) in;

shared float iterate[2][SUBDFIT_PRECONDITION_ONE_GROUP];

uniform int uIterations;

void main() {
    const int floats = SUBDFIT_CHANNELS * uVertexCount;
    for (int i = int(gl_LocalInvocationIndex); i < floats; i += 256)
        iterate[0][i] = texelFetch(gradient, i / SUBDFIT_CHANNELS)[i % SUBDFIT_CHANNELS];
    barrier();
    for (int k = 0; k < uIterations; ++k) {
        const int from = k & 1, to = from ^ 1;
        for (int v = int(gl_LocalInvocationIndex); v < uVertexCount; v += 256) {
            int begin = texelFetch(adjacencyOffsets, v).x, end = texelFetch(adjacencyOffsets, v + 1).x;
            vec4 neighbourSum = vec4(0.0), current = vec4(0.0);
            for (int n = begin; n < end; ++n) {
                int j = SUBDFIT_CHANNELS * texelFetch(adjacencyIndices, n).x;
                for (int c = 0; c < SUBDFIT_CHANNELS; ++c) neighbourSum[c] += iterate[from][j + c];
            }
            for (int c = 0; c < SUBDFIT_CHANNELS; ++c) current[c] = iterate[from][SUBDFIT_CHANNELS * v + c];
            float scale = 1.0 / (1.0 + uLambda * float(end - begin));
            vec4 smoothed = jacobi(current, texelFetch(gradient, v), neighbourSum, scale);
            for (int c = 0; c < SUBDFIT_CHANNELS; ++c) iterate[to][SUBDFIT_CHANNELS * v + c] = smoothed[c];
        }
        barrier();
    }
    for (int i = int(gl_LocalInvocationIndex); i < floats; i += 256) smoothOut[i] = iterate[uIterations & 1][i];
}
#else
// One sweep per dispatch.
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
