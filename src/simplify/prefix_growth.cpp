#include "simplify/prefix_growth.h"

#include <bit>

#include "simplify/bake/bake.h"
#include "util/error.h"

namespace subdfit::simplify {

std::string whyNotGrown(const codec::SubdAsset& asset) {
    const surface::SurfaceMaps& m = asset.maps;
    if (!m.hasDisplacement()) return "it has no heights";
    if (m.hasNormal()) return "it has a normal map";
    if (m.kinds().appearance() || !m.normalTexture.empty() || !m.emissive.empty()) return "it has an appearance";
    return "";
}

namespace {

// Throws unless `asset`'s heights grow to `resolution` (its own times a power of two) at `bits`.
void checkGrowth(const GrowingAsset& asset, int resolution, int bits) {
    const int own = asset.asset.maps.layout.resolution;
    if (own == 0 || resolution % own != 0 || !std::has_single_bit(unsigned(resolution / own)) || bits <= asset.bits)
        throw Error(asset.name + ": heights at T = " + std::to_string(own) + " and " + std::to_string(asset.bits) +
                    " bits grow only to T = " + std::to_string(own) + " times a power of two at more bits, not T = " +
                    std::to_string(resolution) + " at " + std::to_string(bits));
}

}  // namespace

std::vector<float> grownHeights(const GrowingAsset& asset, const mesh::PolygonMesh& reference, int resolution) {
    checkGrowth(asset, resolution, asset.bits + 1);
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
    // The asset's heights on the grown layout: node (i, j) of its tile is (i s, j s) of the grown one.
    std::vector<float> prefixHeights = heights;
    const int s = resolution / own.resolution;
    for (int face = 0; face < own.ptexFaceCount; ++face)
        for (int j = 0; j <= own.resolution; ++j)
            for (int i = 0; i <= own.resolution; ++i)
                prefixHeights[size_t(maps.layout.node(face, i * s, j * s))] =
                    a.maps.displacement[size_t(own.node(face, i, j))];
    const codec::ShippedSubd shipped = codec::readShippedSubd(asset.file, asset.name);
    codec::SubdPrecision precision = codec::SubdPrecision::forMapBits(bits, 90, shipped.positionBits);
    precision.prefix = {.resolution = own.resolution,
                        .bits = asset.bits,
                        .heights = std::move(prefixHeights),
                        .coding = a.heightsCoding,
                        .cageSection = shipped.cageSection};
    return codec::encodeSubd({.cage = a.cage, .maps = maps, .decodeTriangles = a.decodeTriangles}, precision);
}

Growth growWithinBudget(const GrowingAsset& asset, const mesh::PolygonMesh& reference, std::uintmax_t budget,
                        const std::function<double(const codec::SubdAsset&)>& loss) {
    Growth growth;
    growth.assetLoss = loss(asset.asset);
    constexpr int kMostBits = 8;
    for (int resolution = 2 * asset.asset.maps.layout.resolution; resolution <= kMostGrownResolution; resolution *= 2) {
        const std::vector<float> heights = grownHeights(asset, reference, resolution);
        std::vector<unsigned char> file;
        int bits = kMostBits;
        for (; bits > asset.bits; --bits)
            if (file = grownFile(asset, heights, resolution, bits); file.size() <= budget) break;
        if (bits == asset.bits) break;  // finer lattices cost more still
        const GrowthCandidate c{.resolution = resolution,
                                .bits = bits,
                                .bytes = file.size(),
                                .loss = loss(codec::decodeSubd(file, asset.name + " grown"))};
        growth.candidates.push_back(c);
        if (c.loss < growth.assetLoss && (growth.file.empty() || c.loss < growth.chosen.loss)) {
            growth.file = std::move(file);
            growth.chosen = c;
        }
    }
    if (growth.candidates.empty()) growth.why = "no finer heights fit the budget at more bits than the asset's";
    else if (growth.file.empty()) growth.why = "no finer heights that fit the budget draw closer than the asset's";
    return growth;
}

}  // namespace subdfit::simplify
