#pragma once
// What decoding one asset.subd may cost. A few kilobytes of .subd can state a million-face cage,
// a map lattice of a hundred million nodes, a JPEG of 16384² pixels or a gigabyte zstd frame;
// each such count is priced here, from what one of its items costs when decoded, before
// anything of that size is allocated, against one budget for the whole decode (the asset and
// the triangles written from it). The per-item costs are peak bytes measured on the decoder
// itself (docs/limits.md), rounded up.
#include <cstdint>
#include <string>

namespace subdfit::codec {

// What decoding any file may take beyond the program itself (~180 MB of libraries), however
// few bytes it has: with them, under 1 GB.
inline constexpr std::uint64_t kDecodeBudgetBytes = std::uint64_t(768) << 20;

// Peak bytes per decoded item.
struct DecodeCost {
    static constexpr std::uint64_t kCageFace = 512;  // the cage and OpenSubdiv's tables for it
    static constexpr std::uint64_t kCageVertex = 64;
    static constexpr std::uint64_t kLatticeSlot = 48;    // a map lattice's node of one tile, its values
    static constexpr std::uint64_t kAtlasTexel = 8;      // a texture atlas's lattice node
    static constexpr std::uint64_t kAtlasPixel = 32;     // an appearance image: decoded, RGB, node values
    static constexpr std::uint64_t kOutputVertex = 176;  // the tessellation, the glTF mesh, the .glb
    static constexpr std::uint64_t kOutputTriangle = 40;
    // A chain of levels of detail below level 0, per level-0 triangle: level 0 as the levels are
    // measured against (its BVH) and simplified from, and the candidates of each level.
    static constexpr std::uint64_t kLodChainTriangle = 256;
};

class DecodeBudget {
public:
    // `name` names the file in refusals.
    explicit DecodeBudget(std::string name, std::uint64_t bytes = kDecodeBudgetBytes)
        : name_(std::move(name)), left_(bytes), total_(bytes) {}

    // Whether `count` items of `bytesEach` fit what is left (saturating: no count overflows).
    bool fits(std::uint64_t count, std::uint64_t bytesEach) const;
    // Takes them from what is left, or throws subdfit::Error "name: `what` would take about N MB to
    // decode, more than the 768 MB ..." (what: "a cage of 90000 faces").
    void spend(std::uint64_t count, std::uint64_t bytesEach, const std::string& what);
    std::uint64_t left() const { return left_; }
    const std::string& name() const { return name_; }

private:
    std::string name_;
    std::uint64_t left_, total_;
};

}  // namespace subdfit::codec
