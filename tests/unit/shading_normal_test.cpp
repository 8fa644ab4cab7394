// surface::ShadingNormal: heights that only place the surface (the limit normal shades it), as
// simplify ships for a faceted reference, in the CPU twin and through asset.subd.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <cstring>
#include <random>

#include "error_message.h"
#include "codec/subd_format.h"
#include "mesh/procedural.h"
#include "surface/displaced_surface.h"
#include "util/hash.h"

namespace subdfit::test {
namespace {

surface::SurfaceMaps roughHeights(const mesh::PolygonMesh& cage, int resolution, surface::ShadingNormal shading) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, resolution);
    maps.shadingNormal = shading;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> height(-0.03f, 0.03f);
    maps.displacement.resize(size_t(maps.layout.nodeCount));
    for (float& d : maps.displacement) d = height(rng);
    return maps;
}

TEST(ShadingNormal, LimitShadingMovesThePointButNotTheNormal) {
    const auto cage = mesh::makeQuadSphere(3);
    const auto displaced = roughHeights(cage, 4, surface::ShadingNormal::Displaced);
    const auto limitShaded = roughHeights(cage, 4, surface::ShadingNormal::Limit);
    const surface::SurfaceMaps none;
    const surface::DisplacedSurface bumpy(cage, displaced), smooth(cage, limitShaded), bare(cage, none);
    double tilt = 0.0;
    int samples = 0;
    for (int f = 0; f < bare.ptexFaceCount(); ++f)
        for (float u : {0.1f, 0.4f, 0.7f})
            for (float v : {0.2f, 0.5f, 0.9f}) {
                const auto b = bumpy.at(f, u, v), s = smooth.at(f, u, v), limit = bare.at(f, u, v);
                EXPECT_LT(glm::length(s.position - b.position), 1e-6f);     // the heights place both alike
                EXPECT_GT(glm::dot(s.normal, limit.normal), 1.0f - 1e-6f);  // only one is shaded by them
                EXPECT_LT(glm::length(s.dPdu - limit.dPdu) + glm::length(s.dPdv - limit.dPdv), 1e-5f);
                tilt += std::acos(std::min(1.0f, glm::dot(b.normal, limit.normal)));
                ++samples;
            }
    EXPECT_GT(tilt / samples, 0.05);  // the heights do tilt the displaced surface's normal
}

TEST(ShadingNormal, TheChoiceShipsInTheSubdHeader) {
    const auto cage = mesh::makeQuadSphere(3);
    for (const auto shading : {surface::ShadingNormal::Displaced, surface::ShadingNormal::Limit}) {
        const auto bytes = codec::encodeSubd(codec::shippableAsset(cage, roughHeights(cage, 2, shading)));
        EXPECT_EQ(codec::decodeSubd(bytes, "shaded.subd").maps.shadingNormal, shading);
    }
    // Without heights there is nothing for it to say: never set.
    surface::SurfaceMaps bare;
    bare.shadingNormal = surface::ShadingNormal::Limit;
    const auto bytes = codec::encodeSubd(codec::shippableAsset(cage, bare));
    EXPECT_EQ(codec::decodeSubd(bytes, "bare.subd").maps.shadingNormal, surface::ShadingNormal::Displaced);
}

// A header whose flags say what the file cannot mean is refused in one line, checksum or not.
TEST(ShadingNormal, FlagsTheFileCannotMeanAreRefused) {
    const auto cage = mesh::makeQuadSphere(3);
    auto withFlags = [](std::vector<unsigned char> bytes, unsigned char flags) {
        bytes[6] = flags;
        const size_t body = bytes.size() - 8;
        const std::uint64_t sum = hash64({reinterpret_cast<const char*>(bytes.data()), body});
        std::memcpy(bytes.data() + body, &sum, 8);
        return bytes;
    };
    const auto bare = codec::encodeSubd(codec::shippableAsset(cage, {}));
    const auto heights =
        codec::encodeSubd(codec::shippableAsset(cage, roughHeights(cage, 2, surface::ShadingNormal::Displaced)));
    EXPECT_EQ(codec::decodeSubd(withFlags(heights, 1), "ok.subd").maps.shadingNormal, surface::ShadingNormal::Limit);
    const std::string noHeights = errorMessage([&] { codec::decodeSubd(withFlags(bare, 1), "bare.subd"); });
    EXPECT_EQ(noHeights, "bare.subd: limit shading flagged without a displacement");
    const std::string unknown = errorMessage([&] { codec::decodeSubd(withFlags(heights, 4), "new.subd"); });
    EXPECT_EQ(unknown, "new.subd: unknown flags");
}

}  // namespace
}  // namespace subdfit::test
