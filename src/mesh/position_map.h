#pragma once
// Vertices found by their exact position: hashed and compared by the floats' bits, so that hash
// and equality agree (-0 and 0 are two positions, as a file writes them).
#include <bit>
#include <cstdint>
#include <unordered_map>

#include <glm/vec3.hpp>

namespace subdfit::mesh {

struct PositionHash {
    size_t operator()(const glm::vec3& p) const {
        return size_t(std::bit_cast<std::uint32_t>(p.x)) * 0x9E3779B97F4A7C15ull ^
               size_t(std::bit_cast<std::uint32_t>(p.y)) * 0xC2B2AE3D27D4EB4Full ^
               size_t(std::bit_cast<std::uint32_t>(p.z)) * 0x165667B19E3779F9ull;
    }
};

struct SamePosition {
    bool operator()(const glm::vec3& a, const glm::vec3& b) const {
        return std::bit_cast<std::uint32_t>(a.x) == std::bit_cast<std::uint32_t>(b.x) &&
               std::bit_cast<std::uint32_t>(a.y) == std::bit_cast<std::uint32_t>(b.y) &&
               std::bit_cast<std::uint32_t>(a.z) == std::bit_cast<std::uint32_t>(b.z);
    }
};

template <class T>
using PositionMap = std::unordered_map<glm::vec3, T, PositionHash, SamePosition>;

}  // namespace subdfit::mesh
