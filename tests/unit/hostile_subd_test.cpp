// .subd files made to cost what they do not hold: a cage that decodes to millions of triangles
// from two kilobytes, map sections whose counts only a whole texel layout could check, zstd
// frames that inflate a thousandfold, a JPEG whose header promises 16384² pixels, an atlas size
// between the reader's limit and the core's, duplicate creases, control bytes in a tag. Each
// is refused (or decoded within its legitimate cost) in one line naming the file, inside a
// child process with a memory and a time limit (support/bounded_run.h).
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <zstd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bounded_run.h"
#include "error_message.h"
#include "subd_bytes.h"
#include "codec/atlas_uv_coding.h"
#include "codec/byte_stream.h"
#include "codec/cage_coding.h"
#include "export/engine/subd_decode.h"
#include "codec/subd_format.h"
#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "surface/texel_layout.h"
#include "test_paths.h"
#include "util/hash.h"

namespace subdfit::codec {
namespace {

namespace fs = std::filesystem;
using Bytes = std::vector<unsigned char>;
using test::expectRefused;
using test::plainGridCage;
constexpr std::size_t kMB = std::size_t(1) << 20;

struct Section {
    std::string tag;
    Bytes raw;
    Bytes stored = {};         // the zstd frame as written (default: raw compressed)
    std::size_t declared = 0;  // the raw size the header states (default: raw's)
};

Bytes compressed(const Bytes& raw) {
    Bytes stored(ZSTD_compressBound(raw.size()));
    stored.resize(ZSTD_compress(stored.data(), stored.size(), raw.data(), raw.size(), 3));
    return stored;
}

// A version-5 container around the sections.
Bytes container(const std::vector<Section>& sections) {
    ByteWriter file;
    file.putBytes({reinterpret_cast<const unsigned char*>("SUBD"), 4});
    file.put<std::uint16_t>(5);
    file.put<std::uint16_t>(0);
    file.put<std::uint32_t>(std::uint32_t(sections.size()));
    for (const Section& s : sections) {
        const Bytes frame = s.stored.empty() ? compressed(s.raw) : s.stored;
        file.putBytes({reinterpret_cast<const unsigned char*>(s.tag.data()), 4});
        file.put<std::uint32_t>(std::uint32_t(frame.size()));
        file.put<std::uint32_t>(std::uint32_t(s.declared ? s.declared : s.raw.size()));
        file.putBytes(frame);
    }
    const auto& bytes = file.bytes();
    file.put<std::uint64_t>(hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    return std::move(file.bytes());
}

fs::path written(const std::string& name, const Bytes& bytes) {
    const fs::path path = test::scratchDir("hostile_subd") / name;
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
}

Bytes readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A quad sphere with heights (a CAGE and a DISP section).
SubdAsset lumpyAsset() {
    const auto cage = mesh::makeQuadSphere(3);
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 4);
    maps.displacement.resize(size_t(maps.layout.nodeCount));
    for (size_t k = 0; k < maps.displacement.size(); ++k) maps.displacement[k] = 0.01f * float((k * 7919) % 13);
    return shippableAsset(cage, maps);
}

// 40 000 quads in a few kilobytes: at 8 segments a face (the old default) 5 M triangles and a
// gigabyte; by default it decodes to an engine-sized mesh.
TEST(HostileSubd, ALargePlainCageDecodesWithinItsBudgetByDefault) {
    const Bytes file = container({{"CAGE", plainGridCage(200)}});
    EXPECT_LT(file.size(), 8000u);
    const fs::path subd = written("grid200.subd", file), glb = subd.parent_path() / "grid200.glb";
    const auto outcome = test::runBounded(512 * kMB, 60, [&] { exporter::decodeToGlb(subd, glb); });
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    ASSERT_EQ(outcome.error, "");
    EXPECT_LE(mesh::loadMesh(glb).faceCount(), 1 << 20);
}

TEST(HostileSubd, ADensityBeyondTheHardLimitIsRefusedBeforeAllocating) {
    const fs::path subd = written("grid200_64.subd", container({{"CAGE", plainGridCage(200)}}));
    const fs::path glb = subd.parent_path() / "never.glb";
    expectRefused(test::runBounded(256 * kMB, 20, [&] { exporter::decodeToGlb(subd, glb, {.segments = 64}); }),
                  "grid200_64.subd", "triangles");
    EXPECT_FALSE(fs::exists(glb));
}

// Resolution 64 and one node on 20 000 quads: the layout that would show the count is wrong
// holds 84 M nodes.
TEST(HostileSubd, MapCountsAreCheckedAgainstTheCageBeforeTheLayoutIsBuilt) {
    ByteWriter disp;
    disp.putVarint(64);
    disp.putVarint(1);
    disp.put<float>(0.0f);
    disp.put<float>(0.01f);
    for (int k = 0; k < 64; ++k) disp.put<std::uint8_t>(0);
    const fs::path subd = written("disp64.subd", container({{"CAGE", plainGridCage(141)}, {"DISP", disp.bytes()}}));
    expectRefused(test::runBounded(256 * kMB, 10, [&] { readSubd(subd); }), "disp64.subd", "node count");
}

// One section declaring a gigabyte, 30 KB stored: refused on what its header implies, not
// inflated first.
TEST(HostileSubd, AZstdBombIsRefusedBeforeItInflates) {
    const Bytes head = plainGridCage(2);
    const std::size_t rawSize = std::size_t(1) << 30;
    ZSTD_CCtx* context = ZSTD_createCCtx();
    ZSTD_CCtx_setPledgedSrcSize(context, rawSize);
    Bytes frame(ZSTD_compressBound(rawSize / 1024) + 4096);
    ZSTD_outBuffer out{frame.data(), frame.size(), 0};
    const Bytes zeros(kMB, 0);
    std::size_t fed = 0;
    for (ZSTD_inBuffer in{head.data(), head.size(), 0}; in.pos < in.size;)
        ZSTD_compressStream2(context, &out, &in, ZSTD_e_continue);
    fed += head.size();
    while (fed < rawSize) {
        const std::size_t n = std::min(zeros.size(), rawSize - fed);
        ZSTD_inBuffer in{zeros.data(), n, 0};
        while (in.pos < in.size) ZSTD_compressStream2(context, &out, &in, ZSTD_e_continue);
        fed += n;
    }
    ZSTD_inBuffer none{nullptr, 0, 0};
    while (ZSTD_compressStream2(context, &out, &none, ZSTD_e_end) != 0) {}
    ZSTD_freeCCtx(context);
    frame.resize(out.pos);
    EXPECT_LT(frame.size(), 64 * 1024u);
    const Bytes file = container({{.tag = "CAGE", .raw = {}, .stored = frame, .declared = rawSize}});
    const fs::path subd = written("bomb.subd", file);
    expectRefused(test::runBounded(256 * kMB, 20, [&] { readSubd(subd); }), "bomb.subd", "CAGE");
}

TEST(HostileSubd, DuplicateCreasesAreRefused) {
    const std::vector<std::array<int, 2>> creases(1000, std::array<int, 2>{0, 1});
    const std::string message = test::errorMessage([&] {
        decodeSubd(container({{"CAGE", plainGridCage(4, creases)}}), "creases.subd");
    });
    EXPECT_NE(message.find("creases.subd"), std::string::npos) << message;
    EXPECT_NE(message.find("duplicate crease"), std::string::npos) << message;
    // One crease per edge is fine, in either direction.
    EXPECT_NO_THROW(decodeSubd(container({{"CAGE", plainGridCage(4, {{0, 1}, {2, 1}})}}), "two.subd"));
}

// The atlas size 5000 passed the reader (16384) and stopped on an internal check (4096).
TEST(HostileSubd, AnAtlasSizeBeyondTheLimitIsRefusedAtReading) {
    const auto cage = mesh::makeQuadSphere(2);
    const CodedCage coded = encodeCage(cage, 14);
    const int ptex = surface::buildTexelLayout(coded.decoded, 1).ptexFaceCount;
    surface::AppearanceAtlas atlas{.size = 5000,
                                   .cornerUvs = std::vector<glm::vec2>(4 * size_t(ptex), glm::vec2(0.5f))};
    ByteWriter auvs, bcol;
    writeAtlasUvs(coded.decoded, atlas, auvs);
    bcol.putVarint(4999);
    bcol.putVarint(5000 * 5000);
    bcol.put<std::uint8_t>(1);
    bcol.putVarint(1);
    bcol.put<std::uint8_t>(0);
    const Bytes file = container({{"CAGE", coded.bytes}, {"AUVS", auvs.bytes()}, {"BCOL", bcol.bytes()}});
    expectRefused(test::runBounded(256 * kMB, 10, [&] { decodeSubd(file, "atlas.subd"); }), "atlas.subd",
                  "atlas size 5000");
}

// A small JPEG whose SOF0 says 16384 × 16384, as the base colour of a 4-quad cage whose atlas
// is 4 × 4: refused on its header.
TEST(HostileSubd, AnImageIsCheckedAgainstTheAtlasBeforeItIsDecoded) {
    const auto cage = mesh::makeQuadGrid(2);
    const CodedCage coded = encodeCage(cage, 14);
    io::DecodedImage small{16, 16, std::vector<std::uint8_t>(16 * 16 * 4, 128)};
    auto jpeg = io::encodeImage(small, 16, 16, io::ImageFormat::Jpeg);
    for (size_t k = 0; k + 8 < jpeg.size(); ++k)
        if (jpeg[k] == 0xFF && jpeg[k + 1] == 0xC0) {
            for (size_t at : {k + 5, k + 7}) jpeg[at] = 0x40, jpeg[at + 1] = 0x00;  // height, width: 16384
            break;
        }
    ByteWriter bcol;
    bcol.putVarint(1);
    bcol.putVarint(std::uint64_t(surface::buildTexelLayout(coded.decoded, 1).nodeCount));
    bcol.put<std::uint8_t>(1);
    bcol.putVarint(jpeg.size());
    bcol.putBytes({jpeg.data(), jpeg.size()});
    const Bytes file = container({{"CAGE", coded.bytes}, {"BCOL", bcol.bytes()}});
    expectRefused(test::runBounded(256 * kMB, 10, [&] { decodeSubd(file, "jpeg.subd"); }), "jpeg.subd",
                  "16384 x 16384");
}

TEST(HostileSubd, ControlBytesInATagAreNotEchoed) {
    const Bytes file = container({{"CAGE", plainGridCage(2)}, {"\x1b[2J", {1, 2, 3}}});
    const std::string message = test::errorMessage([&] { decodeSubd(file, "tag.subd"); });
    EXPECT_NE(message.find("tag.subd"), std::string::npos) << message;
    EXPECT_EQ(message.find('\x1b'), std::string::npos) << message;
}

// `decode --out` replaces regular files only: a FIFO, a folder, the input itself and an empty
// path are refused before any work, and stay as they were.
TEST(HostileSubd, DecodeWritesOverRegularFilesOnly) {
    const fs::path subd = written("small.subd", container({{"CAGE", plainGridCage(2)}}));
    const fs::path dir = subd.parent_path();
    ASSERT_EQ(mkfifo((dir / "fifo.glb").c_str(), 0600), 0);
    fs::create_directories(dir / "folder.glb");
    for (const auto& [out, problem] :
         std::vector<std::pair<fs::path, std::string>>{{dir / "fifo.glb", "not a regular file"},
                                                       {dir / "folder.glb", "folder"},
                                                       {subd, "is the input"},
                                                       {"", "empty"}}) {
        const std::string message = test::errorMessage([&] { exporter::decodeToGlb(subd, out); });
        EXPECT_NE(message.find(problem), std::string::npos) << out << ": " << message;
    }
    EXPECT_TRUE(fs::is_fifo(dir / "fifo.glb"));
    EXPECT_TRUE(fs::is_directory(dir / "folder.glb"));
    EXPECT_NO_THROW(readSubd(subd));
    std::ofstream(dir / "old.glb") << "old";
    EXPECT_EQ(test::errorMessage([&] { exporter::decodeToGlb(subd, dir / "old.glb"); }),
              "");  // a regular file is replaced
    EXPECT_GT(fs::file_size(dir / "old.glb"), 100u);
}

// Damaged and made whole again (tests/data/damaged-subd): a bit flipped inside a section's zstd
// frame, a JPEG whose Huffman table is unsound. Refused in the line the web decoder gives too
// (tests/web/decode_test.mjs), never decoded to other heights or left to one decoder's leniency.
TEST(HostileSubd, DamageInsideASectionIsRefusedAsEveryDecoderRefusesIt) {
    const fs::path dir = fs::path(SUBDFIT_SOURCE_DIR) / "tests/data/damaged-subd";
    EXPECT_NO_THROW(decodeSubd(readBytes(dir / "box.subd"), "box.subd"));
    EXPECT_EQ(test::errorMessage([&] { decodeSubd(readBytes(dir / "section_bit_flipped.subd"), "flipped.subd"); }),
              "flipped.subd: section DISP fails its checksum (damaged)");
    EXPECT_EQ(
        test::errorMessage([&] { readShippedSubd(readBytes(dir / "jpeg_huffman_table_damaged.subd"), "jpeg.subd"); }),
        "jpeg.subd: BCOL section: a damaged JPEG (a bad Huffman table)");

    // Bits of every section's frame, here of a freshly encoded asset with heights: each flip is
    // refused, or, where zstd never reads the bit (a frame's don't-care bits), decodes to the
    // same cage and heights; never to others.
    const Bytes good = encodeSubd(lumpyAsset());
    const SubdAsset decoded = decodeSubd(good, "good.subd");
    for (std::size_t at = 16; at + 12 < good.size() - 8;) {
        std::uint32_t storedSize;
        std::memcpy(&storedSize, good.data() + at + 4, 4);
        const std::string tag(reinterpret_cast<const char*>(good.data() + at), 4);
        int refused = 0;
        for (const std::size_t within : {storedSize / 3, storedSize / 2, 2 * storedSize / 3}) {
            Bytes flipped = good;
            flipped[at + 12 + within] ^= 0x01;
            const std::uint64_t sum = hash64({reinterpret_cast<const char*>(flipped.data()), flipped.size() - 8});
            std::memcpy(flipped.data() + flipped.size() - 8, &sum, 8);
            // Its checksum fails, or, in a frame of several blocks (the heights' levels), a block
            // breaks before the checksum is reached.
            const std::string message = test::errorMessage([&] { decodeSubd(flipped, "f.subd"); });
            if (message.empty()) {
                const SubdAsset same = decodeSubd(flipped, "f.subd");
                EXPECT_EQ(same.cage.positions, decoded.cage.positions) << tag << " +" << within;
                EXPECT_EQ(same.maps.displacement, decoded.maps.displacement) << tag << " +" << within;
                continue;
            }
            ++refused;
            EXPECT_EQ(message.rfind("f.subd: section " + tag + " ", 0), 0u) << message;
            EXPECT_NE(message.find("damaged"), std::string::npos) << message;
        }
        EXPECT_GE(refused, 1) << tag;
        at += 12 + storedSize;
    }
}

// A version-7 section stored without a checksum of its content is refused: a reader could not
// tell damage from data.
TEST(HostileSubd, AVersion7SectionWithoutAChecksumIsRefused) {
    Bytes file = container({{"CAGE", plainGridCage(2)}});
    file[4] = 7;  // version 7 (the container writes 5, with no decode triangles: insert them)
    file.insert(file.begin() + 12, {0, 0, 0, 0});
    const std::uint64_t sum = hash64({reinterpret_cast<const char*>(file.data()), file.size() - 8});
    std::memcpy(file.data() + file.size() - 8, &sum, 8);
    EXPECT_EQ(test::errorMessage([&] { decodeSubd(file, "bare.subd"); }),
              "bare.subd: section CAGE has no checksum of its content");
}

}  // namespace
}  // namespace subdfit::codec
