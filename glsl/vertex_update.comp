// A small cage's vertex update in one work group of 256, one dispatch where the passes apart
// take four and a buffer clear (their fixed cost, on a GPU, outweighs a small cage's work):
//   g = G's sums resolved, the sums cleared (resolve_gradient.comp);
//   g̃ = (I + λL)⁻¹ g, the sweeps in shared memory (jacobi.glsl);
//   with SUBDFIT_PROJECT_TANGENTIAL, g̃ −= (1 − keep) P g̃ (project_gradient.comp);
//   with SUBDFIT_ADAM_SHARED_MOMENT, v ← β2 v + (1 − β2) mean g̃² (shared_moment.comp);
//   θ −= Adam's step (adam.glsl).
// Each stage computes what its pass computes, in the same order.
#include "bindings.h"
#include "fixed_point.glsl"
#include "jacobi.glsl"
#include "adam.glsl"
#ifdef SUBDFIT_PROJECT_TANGENTIAL
#include "tangent_frame.glsl"
#endif

layout(local_size_x = 256) in;

layout(std430, binding = SUBDFIT_SSBO_THETA) buffer Theta { float theta[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SUM) buffer Sum { uint sum[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT) coherent buffer Gradient { float gradient[]; };
layout(std430, binding = SUBDFIT_SSBO_GRADIENT_SMOOTH) writeonly buffer Smooth { float gradientSmooth[]; };
layout(std430, binding = SUBDFIT_SSBO_GROUP_MOMENT2) buffer GroupMoment2 { float groupMoment2; };

uniform int uIterations;
uniform float uKeep;

vec4 gradientOf(int v) {
    vec4 g = vec4(0.0);
    for (int c = 0; c < SUBDFIT_CHANNELS; ++c) g[c] = gradient[SUBDFIT_CHANNELS * v + c];
    return g;
}

vec3 point(int v) { return vec3(theta[3 * v], theta[3 * v + 1], theta[3 * v + 2]); }

void main() {
    const int floats = SUBDFIT_CHANNELS * uVertexCount, lane = int(gl_LocalInvocationIndex);
    for (int i = lane; i < floats; i += 256) {
        float g = fromFixed(sum[2 * i], sum[2 * i + 1]);
        sum[2 * i] = 0u;
        sum[2 * i + 1] = 0u;
        gradient[i] = g;
        iterate[0][i] = g;
    }
    memoryBarrierBuffer();  // the sweeps read g back from other lanes
    barrier();
    const int result = sweepInSharedMemory(uIterations), spare = result ^ 1;

#ifdef SUBDFIT_PROJECT_TANGENTIAL
    // A vertex's own channels: no other lane reads them before the barrier.
    for (int v = lane; v < uVertexCount; v += 256) {
        vec3 d = vec3(iterate[result][3 * v], iterate[result][3 * v + 1], iterate[result][3 * v + 2]);
        d -= (1.0 - uKeep) * tangentialPart(v, d);
        for (int c = 0; c < 3; ++c) iterate[result][3 * v + c] = d[c];
    }
    barrier();
#endif

#ifdef SUBDFIT_ADAM_SHARED_MOMENT
    // The mean square reduced in the spare iterate, as shared_moment.comp does in its own array.
    float partial = 0.0;
    for (int i = lane; i < floats; i += 256) {
        float g = iterate[result][i];
        if (!isnan(g) && !isinf(g)) partial += g * g;
    }
    iterate[spare][lane] = partial;
    barrier();
    for (int stride = 128; stride > 0; stride >>= 1) {
        if (lane < stride) iterate[spare][lane] += iterate[spare][lane + stride];
        barrier();
    }
    const float groupV = mix(iterate[spare][0] / float(max(floats, 1)), groupMoment2, uBeta2);
    barrier();  // every lane has read the old moment
    if (lane == 0) groupMoment2 = groupV;
#else
    const float groupV = -1.0;
#endif

    for (int i = lane; i < floats; i += 256) {
        float g = iterate[result][i];
        gradientSmooth[i] = g;
        theta[i] -= adamStep(uint(i), g, groupV);
    }
}
