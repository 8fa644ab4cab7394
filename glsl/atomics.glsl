// Float accumulators in SSBOs. With GL_NV_shader_atomic_float: native atomicAdd (2-6x faster on
// llvmpipe, far better under contention). Without: a compare-and-swap loop on the float's bits.
// GLSL cannot pass buffers to functions, so the macro declares the buffer and its add function.
#ifdef SUBDFIT_ATOMIC_FLOAT
#define SUBDFIT_DECLARE_ACCUMULATOR(BlockName, bindingIndex, array, addFunction)        \
    layout(std430, binding = bindingIndex) buffer BlockName { float array[]; };         \
    void addFunction(uint i, float value) { atomicAdd(array[i], value); }
#else
#define SUBDFIT_DECLARE_ACCUMULATOR(BlockName, bindingIndex, array, addFunction)        \
    layout(std430, binding = bindingIndex) buffer BlockName { uint array[]; };          \
    void addFunction(uint i, float value) {                                              \
        uint expected = array[i];                                                        \
        for (;;) {                                                                       \
            uint desired = floatBitsToUint(uintBitsToFloat(expected) + value);           \
            uint seen = atomicCompSwap(array[i], expected, desired);                     \
            if (seen == expected) break;                                                 \
            expected = seen;                                                             \
        }                                                                                \
    }
#endif
