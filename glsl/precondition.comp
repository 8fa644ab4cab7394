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

layout(std430, binding = SUBDFIT_SSBO_GRADIENT) readonly buffer Gradient { float gradient[]; };
layout(std430, binding = SUBDFIT_SSBO_SMOOTH_IN) readonly buffer SmoothIn { float smoothIn[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer SmoothOut { float smoothOut[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_OFFSETS) readonly buffer AdjOffsets { int adjacencyOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_INDICES) readonly buffer AdjIndices { int adjacencyIndices[]; };

uniform int uVertexCount;
uniform float uLambda;

// One damped Jacobi update of a float of node i, from the neighbours' sum of the last iterate.
float jacobi(float current, float g, float neighbourSum, float scale) {
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
    for (int i = int(gl_LocalInvocationIndex); i < floats; i += 256) iterate[0][i] = gradient[i];
    barrier();
    for (int k = 0; k < uIterations; ++k) {
        const int from = k & 1, to = from ^ 1;
        for (int v = int(gl_LocalInvocationIndex); v < uVertexCount; v += 256) {
            int begin = adjacencyOffsets[v], end = adjacencyOffsets[v + 1];
            float neighbourSum[SUBDFIT_CHANNELS];
            for (int c = 0; c < SUBDFIT_CHANNELS; ++c) neighbourSum[c] = 0.0;
            for (int n = begin; n < end; ++n) {
                int j = SUBDFIT_CHANNELS * adjacencyIndices[n];
                for (int c = 0; c < SUBDFIT_CHANNELS; ++c) neighbourSum[c] += iterate[from][j + c];
            }
            float scale = 1.0 / (1.0 + uLambda * float(end - begin));
            for (int c = 0; c < SUBDFIT_CHANNELS; ++c) {
                int i = SUBDFIT_CHANNELS * v + c;
                iterate[to][i] = jacobi(iterate[from][i], gradient[i], neighbourSum[c], scale);
            }
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
    int begin = adjacencyOffsets[v], end = adjacencyOffsets[v + 1];
    float neighbourSum[SUBDFIT_CHANNELS];
    for (int c = 0; c < SUBDFIT_CHANNELS; ++c) neighbourSum[c] = 0.0;
    for (int k = begin; k < end; ++k) {
        int j = SUBDFIT_CHANNELS * adjacencyIndices[k];
        for (int c = 0; c < SUBDFIT_CHANNELS; ++c) neighbourSum[c] += smoothIn[j + c];
    }
    float scale = 1.0 / (1.0 + uLambda * float(end - begin));
    for (int c = 0; c < SUBDFIT_CHANNELS; ++c) {
        int i = SUBDFIT_CHANNELS * v + c;
        smoothOut[i] = jacobi(smoothIn[i], gradient[i], neighbourSum[c], scale);
    }
}
#endif
