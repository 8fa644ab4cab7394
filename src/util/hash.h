#pragma once
// Content hashes (xxHash's XXH3): the identity of an input file, the checksum of a checkpoint,
// the short suffix that makes a batch output name unique. Not cryptographic: they catch damage
// and mix-ups, not an adversary forging a collision.
#include <cstdint>
#include <string>
#include <string_view>

namespace subdfit {

std::uint64_t hash64(std::string_view bytes);

// Lower-case hex of the low `digits` nibbles, most significant first.
std::string hexDigits(std::uint64_t value, int digits = 16);

}  // namespace subdfit
