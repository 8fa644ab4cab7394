#include "util/hash.h"

#include <xxhash.h>

namespace subdfit {

std::uint64_t hash64(std::string_view bytes) { return XXH3_64bits(bytes.data(), bytes.size()); }

std::string hexDigits(std::uint64_t value, int digits) {
    std::string text(size_t(digits), '0');
    for (int i = digits - 1; i >= 0; --i, value >>= 4) text[size_t(i)] = "0123456789abcdef"[value & 15];
    return text;
}

}  // namespace subdfit
