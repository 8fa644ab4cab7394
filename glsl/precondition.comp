// Large-steps style preconditioning of the vertex gradient: g̃ = (I + λL)⁻¹ g with L the cage's
// uniform graph Laplacian, by damped Jacobi iterations
//     g̃ ← (1 − ω) g̃ + ω (g + λ Σ_j∈N(i) g̃_j) / (1 + λ|N(i)|).
// Plain Jacobi (ω = 1) flips the sign of the checkerboard mode every sweep without shrinking
// it when λ is large; ω = 2/3 damps every high-frequency mode, which is the point here.
// It spreads each noisy per-vertex estimate over the neighbourhood, so the cage moves smoothly
// and cannot tangle, while leaving the low-frequency (shape) part of the gradient intact.
#include "bindings.h"

layout(local_size_x = 128) in;

layout(std430, binding = SUBDFIT_SSBO_GRADIENT) readonly buffer Gradient { float gradient[]; };
layout(std430, binding = SUBDFIT_SSBO_SMOOTH_IN) readonly buffer SmoothIn { float smoothIn[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer SmoothOut { float smoothOut[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_OFFSETS) readonly buffer AdjOffsets { int adjacencyOffsets[]; };
layout(std430, binding = SUBDFIT_SSBO_ADJACENCY_INDICES) readonly buffer AdjIndices { int adjacencyIndices[]; };

uniform int uVertexCount;
uniform float uLambda;

void main() {
    int v = int(gl_GlobalInvocationID.x);
    if (v >= uVertexCount) return;
    vec3 neighbourSum = vec3(0.0);
    int begin = adjacencyOffsets[v], end = adjacencyOffsets[v + 1];
    for (int k = begin; k < end; ++k) {
        int j = adjacencyIndices[k];
        neighbourSum += vec3(smoothIn[3 * j], smoothIn[3 * j + 1], smoothIn[3 * j + 2]);
    }
    vec3 g = vec3(gradient[3 * v], gradient[3 * v + 1], gradient[3 * v + 2]);
    const float omega = 2.0 / 3.0;
    vec3 previous = vec3(smoothIn[3 * v], smoothIn[3 * v + 1], smoothIn[3 * v + 2]);
    vec3 jacobi = (g + uLambda * neighbourSum) / (1.0 + uLambda * float(end - begin));
    vec3 result = mix(previous, jacobi, omega);
    smoothOut[3 * v] = result.x;
    smoothOut[3 * v + 1] = result.y;
    smoothOut[3 * v + 2] = result.z;
}
