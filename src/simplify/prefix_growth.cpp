#include "simplify/prefix_growth.h"

#include <algorithm>
#include <bit>

#include "simplify/bake/bake.h"
#include "util/error.h"

namespace subdfit::simplify {

std::string whyNotGrown(const codec::SubdAsset& asset) {
    const surface::SurfaceMaps& m = asset.maps;
    if (m.hasNormal()) return "it has a normal map";
    if (m.kinds().appearance() || !m.normalTexture.empty() || !m.emissive.empty()) return "it has an appearance";
    return "";
}

namespace {

// The fewest bits a bare cage's heights grow at (the budget search's fewest).
constexpr int kFewestBits = 4, kMostBits = 8;
// Lattices are tried finer and finer until this many in a row score behind the best (as the
// budget search's cage ladder ends): each is a bake of the whole cage, finer ones the costliest.
constexpr int kTrailingLattices = 2;

// Throws unless `asset`'s heights grow to `resolution` (a bare cage: any; else its own times a
// power of two) at `bits`.
void checkGrowth(const GrowingAsset& asset, int resolution, int bits) {
    const int own = asset.asset.maps.layout.resolution;
    if (own == 0) {
        if (resolution >= 1 && resolution <= kMostGrownResolution && bits >= kFewestBits) return;
        throw Error(asset.name + ": a bare cage grows heights at T = 1 to " + std::to_string(kMostGrownResolution) +
                    " and at least " + std::to_string(kFewestBits) + " bits, not T = " + std::to_string(resolution) +
                    " at " + std::to_string(bits));
    }
    if (resolution % own != 0 || !std::has_single_bit(unsigned(resolution / own)) || bits <= asset.bits)
        throw Error(asset.name + ": heights at T = " + std::to_string(own) + " and " + std::to_string(asset.bits) +
                    " bits grow only to T = " + std::to_string(own) + " times a power of two at more bits, not T = " +
                    std::to_string(resolution) + " at " + std::to_string(bits));
}

}  // namespace

GrowingAsset growingAsset(std::span<const unsigned char> file, const std::string& name, int bits) {
    codec::ShippedSubd shipped = codec::readShippedSubd(file, name);
    return {.asset = codec::decodeSubd(file, name),
            .cageSection = std::move(shipped.cageSection),
            .positionBits = shipped.positionBits,
            .bits = bits,
            .name = name};
}

std::vector<float> grownHeights(const GrowingAsset& asset, const mesh::PolygonMesh& reference, int resolution) {
    checkGrowth(asset, resolution, std::max(asset.bits + 1, kFewestBits));
    BakeOptions bake;
    bake.effects = {maps::MapKind::Displacement};
    bake.resolution = resolution;
    return bakeMaps(asset.asset.cage, reference, bake).displacement;
}

std::vector<unsigned char> grownFile(const GrowingAsset& asset, const std::vector<float>& heights, int resolution,
                                     int bits) {
    const codec::SubdAsset& a = asset.asset;
    const surface::TexelLayout& own = a.maps.layout;
    checkGrowth(asset, resolution, bits);
    surface::SurfaceMaps maps = a.maps;
    maps.layout = surface::buildTexelLayout(a.cage, resolution);
    maps.displacement = heights;
    codec::SubdPrecision precision = codec::SubdPrecision::forMapBits(bits, 90, asset.positionBits);
    precision.prefix.cageSection = asset.cageSection;
    if (own.resolution > 0) {
        // The asset's heights on the grown layout: node (i, j) of its tile is (i s, j s) of the grown one.
        std::vector<float> prefixHeights = heights;
        const int s = resolution / own.resolution;
        for (int face = 0; face < own.ptexFaceCount; ++face)
            for (int j = 0; j <= own.resolution; ++j)
                for (int i = 0; i <= own.resolution; ++i)
                    prefixHeights[size_t(maps.layout.node(face, i * s, j * s))] =
                        a.maps.displacement[size_t(own.node(face, i, j))];
        precision.prefix.resolution = own.resolution;
        precision.prefix.bits = asset.bits;
        precision.prefix.heights = std::move(prefixHeights);
        precision.prefix.coding = a.heightsCoding;
    }
    return codec::encodeSubd({.cage = a.cage, .maps = maps, .decodeTriangles = a.decodeTriangles}, precision);
}

Growth growWithinBudget(const GrowingAsset& asset, const mesh::PolygonMesh& reference, std::uintmax_t budget,
                        const std::function<double(const codec::SubdAsset&)>& loss) {
    Growth growth;
    growth.assetLoss = loss(asset.asset);
    const int own = asset.asset.maps.layout.resolution;
    std::vector<int> resolutions(kBareCageResolutions.begin(), kBareCageResolutions.end());
    if (own > 0) {
        resolutions.clear();
        for (int r = 2 * own; r <= kMostGrownResolution; r *= 2) resolutions.push_back(r);
    }
    const int fewestBits = std::max(asset.bits + 1, kFewestBits);
    int trailing = 0;  // lattices in a row scored behind the best so far
    for (const int resolution : resolutions) {
        if (trailing == kTrailingLattices) break;  // finer ones cost more bakes for less
        const std::vector<float> heights = grownHeights(asset, reference, resolution);
        std::vector<unsigned char> file;
        int bits = kMostBits;
        for (; bits >= fewestBits; --bits)
            if (file = grownFile(asset, heights, resolution, bits); file.size() <= budget) break;
        if (bits < fewestBits) break;  // finer lattices cost more still
        const GrowthCandidate c{.resolution = resolution,
                                .bits = bits,
                                .bytes = file.size(),
                                .loss = loss(codec::decodeSubd(file, asset.name + " grown"))};
        growth.candidates.push_back(c);
        if (c.loss < growth.assetLoss && (growth.file.empty() || c.loss < growth.chosen.loss)) {
            growth.file = std::move(file);
            growth.chosen = c;
            trailing = 0;
        } else {
            ++trailing;
        }
    }
    const std::string heights = own > 0 ? "finer heights" : "heights on its cage";
    if (growth.candidates.empty()) growth.why = "no " + heights + " fit the budget";
    else if (growth.file.empty()) growth.why = "no " + heights + " that fit the budget draw closer than the asset";
    return growth;
}

}  // namespace subdfit::simplify
