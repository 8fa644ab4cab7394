#pragma once
// Sizes read from files are multiplied only once the product is known to fit: a × b > limit is
// asked as b > limit / a, which cannot wrap (a count of 2^62 + 1 times a stride of 4 is 4 in
// 64-bit arithmetic).
#include <cstdint>

namespace subdfit {

inline bool productExceeds(std::uint64_t a, std::uint64_t b, std::uint64_t limit) { return a != 0 && b > limit / a; }

inline bool productExceeds(std::uint64_t a, std::uint64_t b, std::uint64_t c, std::uint64_t limit) {
    return productExceeds(a, b, limit) || productExceeds(a * b, c, limit);
}

}  // namespace subdfit
