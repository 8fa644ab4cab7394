#pragma once
// `simplify --prefix`: a shipped asset.subd grown into a larger file whose first bytes are that
// asset (codec::EmbeddedPrefix): its cage section byte for byte, then heights baked from the
// reference: on a bare cage at any resolution; on an asset with heights at its resolution times
// a power of two, whose coarse levels hold the asset's own heights on their own grid. A stream
// of the file draws the asset once its bytes are in and refines it as the rest arrives
// (docs/asset-subd-format.md, "Prefixes").
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "codec/subd_format.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

// Why `asset` (as decoded) cannot grow; "" where it can: a cage, bare or with heights alone (a
// normal map or an appearance would not be its own byte for byte in the grown file).
std::string whyNotGrown(const codec::SubdAsset& asset);

// An asset.subd to grow, read once (growingAsset): decoded, the bytes of its cage section and
// its position bits (which the grown file keeps), and the bits its heights were coded at.
struct GrowingAsset {
    codec::SubdAsset asset;
    std::vector<unsigned char> cageSection;
    int positionBits = 0;
    int bits = 0;      // 0: a bare cage
    std::string name;  // in errors
};

// `file`, a shipped asset.subd whose heights were coded at `bits` (0: none), to grow.
GrowingAsset growingAsset(std::span<const unsigned char> file, const std::string& name, int bits);

// The heights `asset` holds, baked from `reference` (triangles, world units) at `resolution`.
std::vector<float> grownHeights(const GrowingAsset& asset, const mesh::PolygonMesh& reference, int resolution);

// The grown file of `heights` (grownHeights at `resolution`: a bare cage's any, else a
// power-of-two multiple of the asset's) at `bits` (more than the asset's): its first bytes
// decode to the asset node for node.
std::vector<unsigned char> grownFile(const GrowingAsset& asset, const std::vector<float>& heights, int resolution,
                                     int bits);

// One grown file weighed: its lattice, bits, bytes and loss (the caller's measure of the decoded
// file; lower is better).
struct GrowthCandidate {
    int resolution = 0, bits = 0;
    std::uintmax_t bytes = 0;
    double loss = 0.0;
};

struct Growth {
    std::vector<unsigned char> file;  // the best grown file; empty where none beats the asset
    GrowthCandidate chosen;           // its figures
    double assetLoss = 0.0;           // the asset's own
    std::vector<GrowthCandidate> candidates;
    std::string why;  // where none ships: why
};

// The largest resolution grown to, the budget search's finest (T = 16 on a 6 500-face cage passes
// llvmpipe's largest storage block: docs/limits.md); a bare cage's heights at the search's
// resolutions.
inline constexpr int kMostGrownResolution = 8;
inline constexpr std::array kBareCageResolutions{2, 3, 4, 6, 8};

// For each resolution (a bare cage's kBareCageResolutions, else the asset's times 2, 4, ... up
// to kMostGrownResolution), the most bits (up to 8; at least 4 on a bare cage, else more than the
// asset's) whose file fits `budget`, weighed by `loss`; the least loss ships where it is below
// the asset's. Larger lattices are not baked once one fits at no bits, or two in a row score
// behind the best.
Growth growWithinBudget(const GrowingAsset& asset, const mesh::PolygonMesh& reference, std::uintmax_t budget,
                        const std::function<double(const codec::SubdAsset&)>& loss);

}  // namespace subdfit::simplify
