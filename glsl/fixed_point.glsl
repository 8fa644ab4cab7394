// Order-independent sums. Float atomics round after every add, so a sum depends on the order in
// which the GPU's threads arrive, and a fit diverges from its own rerun within a few hundred
// steps. These accumulators hold a 64-bit two's-complement fixed-point number with 32
// fractional bits in two uints (low, high) and add with integer atomics: the low word's
// carries reach the high word exactly, so the total is the same in any order.
//
// Resolution 2^-32 (2.3e-10) and range ±2^31 cover G's terms: a pixel adds Δ/(2ε) of at most a
// few hundred, a gradient sums at most millions of them, and the terms that matter are above
// 1e-7. A non-finite or out-of-range value (never expected) is clamped, not spread as NaN.
#ifndef SUBDFIT_FIXED_POINT_GLSL
#define SUBDFIT_FIXED_POINT_GLSL

const float SUBDFIT_FIXED_ONE = 4294967296.0;  // 2^32
const float SUBDFIT_FIXED_MAX = 1073741824.0;  // 2^30: well inside the high word's range

// (low, high) of round-toward-minus-infinity(x · 2^32). Exact for |x| >= 2^-8: x − floor(x) is
// always representable, and scaling by 2^32 is exact.
uvec2 toFixed(float x) {
    x = isnan(x) ? 0.0 : clamp(x, -SUBDFIT_FIXED_MAX, SUBDFIT_FIXED_MAX);
    float whole = floor(x);
    return uvec2(uint((x - whole) * SUBDFIT_FIXED_ONE), uint(int(whole)));
}

float fromFixed(uint low, uint high) { return float(int(high)) + float(low) * (1.0 / SUBDFIT_FIXED_ONE); }

// (a + b) in 64 bits: the low words' carry goes to the high word.
uvec2 addFixed(uvec2 a, uvec2 b) {
    uint low = a.x + b.x;
    return uvec2(low, a.y + b.y + (low < a.x ? 1u : 0u));
}

// Declares `array` (two uints per slot) and its atomic add function.
#define SUBDFIT_DECLARE_FIXED_ACCUMULATOR(BlockName, bindingIndex, array, addFunction)   \
    layout(std430, binding = bindingIndex) buffer BlockName { uint array[]; };           \
    void addFunction(uint i, float value) {                                              \
        uvec2 v = toFixed(value);                                                        \
        uint old = atomicAdd(array[2u * i], v.x);                                        \
        uint high = v.y + (old + v.x < old ? 1u : 0u);                                   \
        if (high != 0u) atomicAdd(array[2u * i + 1u], high);                             \
    }

#endif
