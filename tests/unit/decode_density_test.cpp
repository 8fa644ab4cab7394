// How densely `subdfit decode` tessellates: around the triangle count asset.subd records (the
// reference's), or what --triangles / --tess ask, within the hard limit; files that record none
// (version 5 and before) fall back to a count derived from the cage, and still read.
#include <gtest/gtest.h>

#include <cstring>

#include "error_message.h"
#include "codec/decode_density.h"
#include "export/engine/subd_decode.h"
#include "codec/subd_format.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "test_paths.h"
#include "util/hash.h"

namespace subdfit::codec {
namespace {

// The same file as version 5 wrote it: no decode triangles in the header.
std::vector<unsigned char> asVersion5(std::vector<unsigned char> bytes) {
    bytes.erase(bytes.begin() + 12, bytes.begin() + 16);
    bytes[4] = 5;
    const std::uint64_t sum = hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size() - 8});
    std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    return bytes;
}

TEST(DecodeDensity, FollowsTheRecordedTriangleCountWithinTwice) {
    const auto cage = mesh::makeQuadSphere(6);  // 216 quads
    for (std::uint32_t reference : {500u, 5000u, 50000u, 211000u, 2000000u}) {
        const SubdAsset asset =
            decodeSubd(encodeSubd({.cage = cage, .maps = {}, .decodeTriangles = reference}), "a.subd");
        ASSERT_EQ(asset.decodeTriangles, reference);
        const DecodeDensity d = decodeDensity(asset, {}, "a.subd");
        EXPECT_EQ(d.triangles, 2 * std::int64_t(d.segments) * d.segments * 216);
        if (reference >= 2 * 216) {  // below that the cage itself is the coarsest decode
            EXPECT_LE(double(d.triangles), 2.0 * reference) << reference;
            EXPECT_GE(double(d.triangles), 0.5 * reference) << reference;
        } else {
            EXPECT_EQ(d.segments, 1);
        }
    }
}

TEST(DecodeDensity, AskedForCountsAndSegmentsWithinTheLimit) {
    const SubdAsset asset{.cage = mesh::makeQuadSphere(6), .maps = {}, .decodeTriangles = 100000};
    const DecodeDensity asked = decodeDensity(asset, {.segments = 0, .triangles = 8000}, "a.subd");
    EXPECT_GE(asked.triangles, 4000);
    EXPECT_LE(asked.triangles, 16000);
    EXPECT_EQ(decodeDensity(asset, {.segments = 3, .triangles = 0}, "a.subd").segments, 3);
    EXPECT_EQ(decodeDensity(asset, {.segments = 0, .triangles = 1}, "a.subd").segments, 1);  // at least the cage
    EXPECT_EQ(decodeDensity(asset, {.segments = 0, .triangles = kMaxDecodeTriangles}, "a.subd").segments, 64);
    const std::string tooMany = test::errorMessage(
        [&] { decodeDensity(asset, {.segments = 0, .triangles = kMaxDecodeTriangles + 1}, "a.subd"); });
    EXPECT_NE(tooMany.find("a.subd"), std::string::npos) << tooMany;
    EXPECT_NE(tooMany.find(std::to_string(kMaxDecodeTriangles)), std::string::npos) << tooMany;
    const SubdAsset big{.cage = mesh::makeQuadGrid(300), .maps = {}, .decodeTriangles = 0};
    const std::string dense =
        test::errorMessage([&] { decodeDensity(big, {.segments = 64, .triangles = 0}, "big.subd"); });
    EXPECT_NE(dense.find("big.subd: 64 segments"), std::string::npos) << dense;
    EXPECT_THROW(decodeDensity(asset, {.segments = 2, .triangles = 100}, "a.subd"), OptionError);
}

// An older file records nothing: one vertex per map node (8 segments without maps), at most
// kFallbackTriangles; the 8 000-face cage that once decoded to 3 M triangles stays under it.
TEST(DecodeDensity, OlderFilesStillReadAndFallBackToTheCage) {
    const auto small = mesh::makeQuadSphere(3);
    const auto v6 = encodeSubd({.cage = small, .maps = {}, .decodeTriangles = 1234});
    const SubdAsset old = decodeSubd(asVersion5(v6), "old.subd");
    EXPECT_EQ(old.decodeTriangles, 0u);
    EXPECT_EQ(old.cage.faceIndices, decodeSubd(v6, "new.subd").cage.faceIndices);
    EXPECT_EQ(decodeDensity(old, {}, "old.subd").segments, 8);
    const SubdAsset large{.cage = mesh::makeQuadGrid(90), .maps = {}, .decodeTriangles = 0};  // 8 100 quads
    const DecodeDensity d = decodeDensity(large, {}, "large.subd");
    EXPECT_LE(d.triangles, kFallbackTriangles);
    EXPECT_GE(d.triangles, kFallbackTriangles / 4);
}

TEST(DecodeDensity, DecodeWritesAboutTheRecordedCount) {
    const auto dir = test::scratchDir("decode_density");
    writeSubd(dir / "asset.subd", {.cage = mesh::makeQuadSphere(6), .maps = {}, .decodeTriangles = 30000});
    exporter::decodeToGlb(dir / "asset.subd", dir / "out.glb");
    const int triangles = mesh::loadMesh(dir / "out.glb").faceCount();
    EXPECT_GE(triangles, 15000);
    EXPECT_LE(triangles, 60000);
}

}  // namespace
}  // namespace subdfit::codec
