// A .subd file's first bytes, as a stream delivers them, decode to a coarser asset: the cage
// whole, the heights' levels wholly present exactly as the whole file decodes them, the finer
// nodes interpolated; a prefix that ends before the cage does, or damage in what it holds, is
// refused in one line.
#include <gtest/gtest.h>

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <random>

#include "codec/subd_format.h"
#include "error_message.h"
#include "limit_values.h"
#include "mesh/procedural.h"
#include "simplify/prefix_growth.h"
#include "util/hash.h"

namespace subdfit::codec {
namespace {

using Bytes = std::vector<unsigned char>;

// Heights with detail at every level: a smooth swell and fine noise.
SubdAsset displacedSphere(int resolution, int n = 3) {
    const auto cage = mesh::makeQuadSphere(n);
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, resolution);
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 0.003f);
    maps.displacement = test::valuesOnLimit(cage, maps.layout, [&](glm::vec3 p) {
        return 0.05f * std::sin(4.0f * p.x) * std::cos(3.0f * p.y) + noise(rng);
    });
    return shippableAsset(cage, maps);
}

// Where the section `tag` begins and ends in `file` (its 12-byte head included).
std::pair<size_t, size_t> sectionSpan(const Bytes& file, const char* tag) {
    std::uint32_t count;
    std::memcpy(&count, file.data() + 8, 4);
    size_t at = 16;
    for (std::uint32_t k = 0; k < count; ++k) {
        std::uint32_t stored;
        std::memcpy(&stored, file.data() + at + 4, 4);
        if (std::memcmp(file.data() + at, tag, 4) == 0) return {at, at + 12 + stored};
        at += 12 + stored;
    }
    return {0, 0};
}

SubdAsset prefixOf(const Bytes& file, size_t bytes) {
    return decodeSubd(std::span(file).first(bytes), "prefix.subd", nullptr, {}, SubdEnding::Prefix);
}

// A prefix's levels decode as in the whole file, the map at the resolution of the finest whole
// lattice they make (a file made for it on the same cage holds that), finer with every level.
TEST(SubdPrefix, EveryPrefixPastTheCageDecodesItsLevelsAsTheWholeFileDoes) {
    const SubdAsset asset = displacedSphere(8, 6);  // 216 faces: every level's pass over 1 KB
    const Bytes file = encodeSubd(asset, {.displacementBits = 12});
    const SubdAsset whole = decodeSubd(file, "whole.subd");
    const auto [dispBegin, dispEnd] = sectionSpan(file, "DISP");
    ASSERT_GT(dispBegin, 0u);
    ASSERT_EQ(dispEnd, file.size() - 8) << "the heights are the file's last section";
    const surface::TexelLayout& layout = whole.maps.layout;
    std::vector<int> resolutions;
    // Every 11th byte from the heights' section on, and the whole file last.
    std::vector<size_t> cuts;
    for (size_t bytes = dispBegin; bytes < file.size(); bytes += 11) cuts.push_back(bytes);
    cuts.push_back(file.size());
    for (const size_t bytes : cuts) {
        const SubdAsset prefix = prefixOf(file, bytes);
        ASSERT_EQ(prefix.cage.positions, whole.cage.positions);
        if (!prefix.maps.hasDisplacement()) {  // not even the corners: the bare limit surface
            EXPECT_TRUE(resolutions.empty()) << "the heights went missing again at " << bytes;
            continue;
        }
        const surface::TexelLayout& at = prefix.maps.layout;
        ASSERT_EQ(layout.resolution % at.resolution, 0);
        if (resolutions.empty() || resolutions.back() != at.resolution) resolutions.push_back(at.resolution);
        const int spacing = layout.resolution / at.resolution;
        for (int face = 0; face < at.ptexFaceCount; ++face)
            for (int j = 0; j <= at.resolution; ++j)
                for (int i = 0; i <= at.resolution; ++i)
                    ASSERT_EQ(prefix.maps.displacement[size_t(at.node(face, i, j))],
                              whole.maps.displacement[size_t(layout.node(face, i * spacing, j * spacing))])
                        << bytes;
    }
    // T = 8: the corners (T = 1), u and v at s = 4 (T = 2), at 2 (T = 4), at 1; each level's
    // passes over 1 KB, flushed, so each a coarser asset of its own, in order.
    EXPECT_EQ(resolutions, (std::vector<int>{1, 2, 4, 8}));
}

TEST(SubdPrefix, AWholeFileReadAsAPrefixIsTheWholeFile) {
    const Bytes file = encodeSubd(displacedSphere(4));
    const SubdAsset whole = decodeSubd(file, "a.subd");
    const SubdAsset prefix = prefixOf(file, file.size());
    EXPECT_EQ(prefix.maps.displacement, whole.maps.displacement);
    EXPECT_EQ(prefix.cage.positions, whole.cage.positions);
}

// What a viewer steps a file's prefixes down to (subdfit-view --prefixes): the fewest bytes that
// decode, the bare cage.
TEST(SubdPrefix, TheCagesEndIsTheFewestBytesThatDecode) {
    const Bytes file = encodeSubd(displacedSphere(4));
    const size_t end = cageEnd(file, "a.subd");
    EXPECT_EQ(end, sectionSpan(file, "CAGE").second);
    EXPECT_FALSE(prefixOf(file, end).maps.hasDisplacement());
    EXPECT_THROW(prefixOf(file, end - 1), Error);
    const Bytes bare = encodeSubd({.cage = mesh::makeQuadSphere(3), .maps = {}});
    EXPECT_EQ(cageEnd(bare, "bare.subd"), bare.size() - 8);
}

TEST(SubdPrefix, APrefixEndingBeforeTheCageDoesOrDamagedIsRefusedInOneLine) {
    const Bytes file = encodeSubd(displacedSphere(4));
    const auto [cageBegin, cageEnd] = sectionSpan(file, "CAGE");
    auto refused = [&](const Bytes& bytes, size_t n, const std::string& expected) {
        const std::string message = test::errorMessage([&] { prefixOf(bytes, n); });
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message.rfind("prefix.subd: ", 0), 0u) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << message;
    };
    refused(file, 12, "truncated");
    refused(file, cageBegin + 6, "end before the cage does");
    refused(file, cageEnd - 1, "end before the cage does");
    EXPECT_NO_THROW(prefixOf(file, cageEnd));
    Bytes damaged = file;
    damaged[(cageBegin + cageEnd) / 2] ^= 0x10;  // inside the cage's frame: its checksum says so
    refused(damaged, cageEnd + 20, "CAGE");
    // Read whole, a prefix is still refused: only a reader that asks for a prefix takes one.
    EXPECT_NE(test::errorMessage([&] { decodeSubd(std::span(file).first(cageEnd + 20), "a.subd"); }).find("checksum"),
              std::string::npos);
}

}  // namespace
}  // namespace subdfit::codec

namespace subdfit::codec {
namespace {

// `file` with each section's raw bytes passed through `edit` (by tag), re-framed as encodeSubd
// frames them, as `version`, its checksum made right.
Bytes reframed(const Bytes& file, std::uint16_t version,
               const std::function<void(const std::string&, std::vector<unsigned char>&)>& edit) {
    Bytes out(file.begin(), file.begin() + 16);
    std::memcpy(out.data() + 4, &version, 2);
    std::uint32_t count;
    std::memcpy(&count, file.data() + 8, 4);
    size_t at = 16;
    for (std::uint32_t k = 0; k < count; ++k) {
        std::uint32_t stored, rawSize;
        std::memcpy(&stored, file.data() + at + 4, 4);
        std::memcpy(&rawSize, file.data() + at + 8, 4);
        std::vector<unsigned char> raw(rawSize);
        EXPECT_EQ(ZSTD_decompress(raw.data(), raw.size(), file.data() + at + 12, stored), rawSize);
        edit(std::string(reinterpret_cast<const char*>(file.data() + at), 4), raw);
        std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(), &ZSTD_freeCCtx);
        ZSTD_CCtx_setParameter(context.get(), ZSTD_c_checksumFlag, 1);
        std::vector<unsigned char> frame(ZSTD_compressBound(raw.size()));
        frame.resize(ZSTD_compress2(context.get(), frame.data(), frame.size(), raw.data(), raw.size()));
        const std::uint32_t sizes[2] = {std::uint32_t(frame.size()), std::uint32_t(raw.size())};
        out.insert(out.end(), file.begin() + std::ptrdiff_t(at), file.begin() + std::ptrdiff_t(at) + 4);
        out.insert(out.end(), reinterpret_cast<const unsigned char*>(sizes),
                   reinterpret_cast<const unsigned char*>(sizes) + 8);
        out.insert(out.end(), frame.begin(), frame.end());
        at += 12 + stored;
    }
    const std::uint64_t sum = hash64({reinterpret_cast<const char*>(out.data()), out.size()});
    out.insert(out.end(), reinterpret_cast<const unsigned char*>(&sum),
               reinterpret_cast<const unsigned char*>(&sum) + 8);
    return out;
}

// Version 10 had no coarse passes: where version 11 packs the leans in a byte and states the
// coarse passes in the next, it had the two leans a byte each. Such a file decodes to the heights
// version 11 holds, and a version-11 file that states an impossible embedded coding is refused.
TEST(SubdPrefix, AVersion10FileDecodesAsItDidAndABadCoarseCodingIsRefused) {
    const Bytes file = encodeSubd(displacedSphere(4));
    const SubdAsset current = decodeSubd(file, "v11.subd");
    // T and the node count as varints, center and step: then the leans and the coarse passes.
    auto leansAt = [](const std::vector<unsigned char>& raw) {
        size_t at = 0;
        for (int varints = 0; varints < 2; ++at)
            if (!(raw[at] & 0x80)) ++varints;
        return at + 8;
    };
    const Bytes version10 = reframed(file, 10, [&](const std::string& tag, std::vector<unsigned char>& raw) {
        if (tag != "DISP") return;
        const size_t at = leansAt(raw);
        ASSERT_EQ(raw[at + 1], 0) << "no coarse passes";
        raw[at + 1] = raw[at] >> 4;  // interpolated
        raw[at] &= 15;               // corners
    });
    EXPECT_EQ(decodeSubd(version10, "v10.subd").maps.displacement, current.maps.displacement);
    const Bytes badShift = reframed(file, 11, [&](const std::string& tag, std::vector<unsigned char>& raw) {
        if (tag == "DISP") raw[leansAt(raw) + 1] = 3;  // a shift without coarse passes
    });
    EXPECT_NE(test::errorMessage([&] { decodeSubd(badShift, "bad.subd"); }).find("bad coarse passes"),
              std::string::npos);
}

}  // namespace
}  // namespace subdfit::codec

namespace subdfit::codec {
namespace {

// A file grown from an asset (its cage section byte for byte, finer heights whose coarse levels
// hold the asset's own on its own grid): a prefix of it decodes to the asset's cage and heights
// exactly, and the whole of it to the finer heights within their step.
TEST(SubdPrefix, AGrownFilesPrefixIsTheAssetItGrewFrom) {
    constexpr int kOwn = 2, kGrown = 8;
    const Bytes small = encodeSubd(displacedSphere(kOwn), {.displacementBits = 4});
    const simplify::GrowingAsset asset = simplify::growingAsset(small, "small.subd", 4);
    ASSERT_TRUE(asset.asset.heightsCoding);
    const std::vector<float> heights =
        test::valuesOnLimit(asset.asset.cage, surface::buildTexelLayout(asset.asset.cage, kGrown),
                            [](glm::vec3 p) { return 0.05f * std::sin(4.0f * p.x) * std::cos(3.0f * p.y); });
    const Bytes file = simplify::grownFile(asset, heights, kGrown, 8);
    ASSERT_GT(file.size(), small.size());

    auto isTheAsset = [&](const SubdAsset& prefix) {
        const SubdAsset& a = asset.asset;
        return prefix.cage.positions == a.cage.positions && prefix.cage.faceIndices == a.cage.faceIndices &&
               prefix.maps.layout.resolution == kOwn && prefix.maps.displacement == a.maps.displacement;
    };
    size_t shortest = 0;
    for (size_t bytes = sectionSpan(file, "CAGE").second; bytes < file.size() && shortest == 0; bytes += 7)
        if (isTheAsset(prefixOf(file, bytes))) shortest = bytes;
    ASSERT_GT(shortest, 0u) << "no prefix decodes to the asset";
    std::printf("the asset: %zu bytes; the grown file: %zu, its first %zu bytes the asset\n", small.size(), file.size(),
                shortest);
    EXPECT_LT(double(shortest), 1.1 * double(small.size()));  // its levels' residuals are the asset's own

    const SubdAsset whole = decodeSubd(file, "grown.subd");
    const ChannelQuantisation fine = *whole.heightsCoding;
    ASSERT_EQ(whole.maps.displacement.size(), heights.size());
    for (size_t n = 0; n < heights.size(); ++n)
        ASSERT_LE(std::abs(whole.maps.displacement[n] - heights[n]), 0.5001f * fine.step) << n;
    // It grows only to a power-of-two multiple of its lattice at more bits than its own.
    EXPECT_THROW(simplify::grownFile(asset, heights, 6, 8), Error);
    EXPECT_THROW(simplify::grownFile(asset, heights, kGrown, 4), Error);
}

}  // namespace
}  // namespace subdfit::codec
