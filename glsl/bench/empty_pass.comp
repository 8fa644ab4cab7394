// Next to no work: prices a dispatch and the barrier after it by themselves (subdfit-bench step-cost).
layout(local_size_x = 64) in;

layout(std430, binding = 0) buffer Counter { uint counter; };

void main() {
    if (gl_LocalInvocationIndex == 0u) counter += 1u;
}
