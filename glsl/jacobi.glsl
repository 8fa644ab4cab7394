// Large-steps style preconditioning of a gradient: g̃ = (I + λL)⁻¹ g with L the uniform graph
// Laplacian of the group's parameter graph (cage edges for vertices, the node grids for maps),
// by damped Jacobi iterations
//     g̃ ← (1 − ω) g̃ + ω (g + λ Σ_j∈N(i) g̃_j) / (1 + λ|N(i)|).
// Plain Jacobi (ω = 1) flips the sign of the checkerboard mode every sweep without shrinking
// it when λ is large; ω = 2/3 damps every high-frequency mode, which is the point here. It
// spreads each noisy per-parameter estimate over the neighbourhood, so the group moves smoothly
// and cannot tangle, while the low-frequency (shape) part of the gradient stays intact.
// SUBDFIT_CHANNELS: floats per graph node (3 for vertex positions, 1 for heights, 2 for normals).
#ifndef SUBDFIT_JACOBI_GLSL
#define SUBDFIT_JACOBI_GLSL

#ifndef SUBDFIT_CHANNELS
#define SUBDFIT_CHANNELS 3
#endif

// The graph, read as buffer textures: a fetch gathers, where an SSBO read is a load a lane (one
// lane after another on llvmpipe).
layout(binding = SUBDFIT_UNIT_ADJACENCY_OFFSETS) uniform isamplerBuffer adjacencyOffsets;
layout(binding = SUBDFIT_UNIT_ADJACENCY_INDICES) uniform isamplerBuffer adjacencyIndices;

uniform int uVertexCount;
uniform float uLambda;

// One damped Jacobi update of node i's channels (the first SUBDFIT_CHANNELS of the four), from its
// neighbours' sum of the last iterate.
vec4 jacobi(vec4 current, vec4 g, vec4 neighbourSum, float scale) {
    const float omega = 2.0 / 3.0;
    return mix(current, (g + uLambda * neighbourSum) * scale, omega);
}

#ifdef SUBDFIT_PRECONDITION_ONE_GROUP
// Every sweep in one work group of 256, the iterate in shared memory: a barrier between sweeps
// instead of a dispatch and a memory barrier each, whose fixed cost on a GPU outweighs a small
// group's sweeps. SUBDFIT_PRECONDITION_ONE_GROUP: floats the group holds at most (two iterates
// fit in the 32 KB of shared memory every GL 4.3 implementation has).
shared float iterate[2][SUBDFIT_PRECONDITION_ONE_GROUP];

vec4 gradientOf(int v);  // g at node v: the includer's

// `iterations` sweeps from iterate[0], which the caller has filled (and passed a barrier since).
// Returns which iterate holds the result.
int sweepInSharedMemory(int iterations) {
    for (int k = 0; k < iterations; ++k) {
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
            vec4 smoothed = jacobi(current, gradientOf(v), neighbourSum, scale);
            for (int c = 0; c < SUBDFIT_CHANNELS; ++c) iterate[to][SUBDFIT_CHANNELS * v + c] = smoothed[c];
        }
        barrier();
    }
    return iterations & 1;
}
#endif

#endif
