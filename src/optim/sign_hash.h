#pragma once
// C++ twin of glsl/hash.glsl: the perturbation sign of parameter i at counter c is a pure
// function of (i, c, seed), so G recomputes what P used without storing it, and the CPU can
// reproduce any step exactly. Integer arithmetic only; a GL test checks bit-for-bit agreement.
#include <cstdint>

namespace subdfit::optim {

constexpr std::uint32_t pcgHash(std::uint32_t v) {
    const std::uint32_t state = v * 747796405u + 2891336453u;
    const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

constexpr float perturbationSign(std::uint32_t parameter, std::uint32_t counter, std::uint32_t seed) {
    const std::uint32_t h = pcgHash(parameter ^ pcgHash(counter ^ pcgHash(seed)));
    return (h & 0x80000000u) != 0u ? 1.0f : -1.0f;
}

}  // namespace subdfit::optim
