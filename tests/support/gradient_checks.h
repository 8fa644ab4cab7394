#pragma once
// What the GL tests compare gradients and compiled variants with.
#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "gl/program_cache.h"

namespace subdfit::test {

// The cosine of the angle between two gradients (1: the same direction).
inline double cosine(const std::vector<double>& a, const std::vector<double>& b) {
    const double ab = std::inner_product(a.begin(), a.end(), b.begin(), 0.0);
    return ab / std::sqrt(std::inner_product(a.begin(), a.end(), a.begin(), 0.0) *
                          std::inner_product(b.begin(), b.end(), b.begin(), 0.0));
}

// Whether any program the cache compiled (so any pass that ran) had `define`.
inline bool anyVariantDefines(const gl::ProgramCache& cache, const std::string& define) {
    for (const auto& v : cache.variants())
        if (v.defines.count(define)) return true;
    return false;
}

}  // namespace subdfit::test
