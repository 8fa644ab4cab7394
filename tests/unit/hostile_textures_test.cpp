// Images made to cost what a reference does not need: a PNG whose header promises 16384² pixels
// (behind an MTL map, a glTF image, a data: URI), several that together pass any per-image cap,
// one file named by eight images, an image no material uses; decompression bombs within the
// per-image cap (a 0.5 MB PNG of 11585² pixels, its 16-bit twin, a 12 KB JPEG whose frame says
// 11585², the same named by eight images and five slots), an EXR of 4000 channels, a GIF claiming
// 65535², a truncated PNG; and KHR_texture_transform numbers beyond any float. Each image's header
// is read first: refused in one line naming the file, or decoded once at no more than subdfit
// uses, inside a child process with a memory and a time limit (support/bounded_run.h).
#include <gtest/gtest.h>
#include <zlib.h>

#include <OpenImageIO/imageio.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "bounded_run.h"
#include "error_message.h"
#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "test_paths.h"
#include "util/warnings.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;
using test::expectRefused;
constexpr std::size_t kMB = std::size_t(1) << 20;

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::uint32_t crc32(const std::string& bytes) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char b : bytes) {
        crc ^= b;
        for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
}

void putBigEndian(std::string& out, std::uint32_t v) {
    for (int shift : {24, 16, 8, 0}) out += char((v >> shift) & 0xFF);
}

void putChunk(std::string& out, const std::string& type, const std::string& data) {
    putBigEndian(out, std::uint32_t(data.size()));
    out += type + data;
    putBigEndian(out, crc32(type + data));
}

// A PNG of a few hundred bytes whose header says width × height RGB pixels; its data stops
// after the first rows (`salt` makes files of equal size differ).
std::string bombPng(std::uint32_t width, std::uint32_t height, char salt = 0) {
    std::string png = "\x89PNG\r\n\x1a\n", header;
    putBigEndian(header, width);
    putBigEndian(header, height);
    header += std::string("\x08\x02\x00\x00\x00", 5);
    putChunk(png, "IHDR", header);
    // A zlib stream of stored blocks of zero rows (filter 0), cut short.
    std::string idat = "\x78\x01";
    for (int block = 0; block < 4; ++block) {
        idat += std::string("\x00\xff\x7f\x00\x80", 5);
        idat += std::string(0x7fff, salt);
    }
    putChunk(png, "IDAT", idat);
    putChunk(png, "IEND", "");
    return png;
}

// A whole PNG of width × height zero pixels (RGBA, 8 or 16 bits), deflated: half a megabyte for
// 11585² pixels at 8 bits. `interlaced` marks it Adam7 (its rows then not what a reader may
// stream; the data is the plain layout, for a reader that refuses on the header alone).
std::string zeroPng(std::uint32_t width, std::uint32_t height, int bitDepth = 8, bool interlaced = false) {
    std::string png = "\x89PNG\r\n\x1a\n", header;
    putBigEndian(header, width);
    putBigEndian(header, height);
    header += char(bitDepth);
    header += std::string("\x06\x00\x00", 3);
    header += char(interlaced ? 1 : 0);
    putChunk(png, "IHDR", header);
    const std::string row(1 + std::size_t(width) * 4 * std::size_t(bitDepth / 8), '\0');
    z_stream z{};
    deflateInit(&z, 9);
    std::string idat;
    std::vector<unsigned char> out(1 << 16);
    for (std::uint32_t y = 0; y <= height; ++y) {
        z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(row.data()));
        z.avail_in = y < height ? uInt(row.size()) : 0;
        do {
            z.next_out = out.data();
            z.avail_out = uInt(out.size());
            deflate(&z, y < height ? Z_NO_FLUSH : Z_FINISH);
            idat.append(reinterpret_cast<const char*>(out.data()), out.size() - z.avail_out);
        } while (z.avail_out == 0);
    }
    deflateEnd(&z);
    putChunk(png, "IDAT", idat);
    putChunk(png, "IEND", "");
    return png;
}

// A real JPEG of a few KB whose frame header is made to say width × height: its data covers a
// small corner, the rest is missing.
std::string lyingJpeg(int width, int height) {
    io::DecodedImage small{64, 64, std::vector<std::uint8_t>(64 * 64 * 4)};
    for (size_t k = 0; k < small.rgba.size(); ++k) small.rgba[k] = std::uint8_t(k * 7);
    const auto bytes = io::encodeImage(small, 64, 64, io::ImageFormat::Jpeg, 90);
    std::string jpeg(bytes.begin(), bytes.end());
    for (size_t at = 2; at + 9 < jpeg.size();) {
        const unsigned char marker = std::uint8_t(jpeg[at + 1]);
        const size_t length = size_t(std::uint8_t(jpeg[at + 2])) << 8 | std::uint8_t(jpeg[at + 3]);
        if (marker == 0xC0 || marker == 0xC2) {
            jpeg[at + 5] = char(height >> 8), jpeg[at + 6] = char(height & 0xFF);
            jpeg[at + 7] = char(width >> 8), jpeg[at + 8] = char(width & 0xFF);
            return jpeg;
        }
        at += 2 + length;
    }
    ADD_FAILURE() << "no frame header in the encoded JPEG";
    return jpeg;
}

// One quad whose material's base colour is `image` (a file beside it).
void writeTexturedObj(const fs::path& dir, const std::string& image) {
    writeText(dir / "m.mtl", "newmtl x\nmap_Kd " + image + "\n");
    writeText(dir / "m.obj",
              "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl x\nf 1/1 2/2 3/3\n");
}

// Loads `file` in a bounded child, which throws unless it decoded its images at no more than
// subdfit uses (at most `side` on a side) and within `pixels` together.
test::BoundedOutcome loadWithinUse(const fs::path& file, std::size_t memory, unsigned seconds,
                                   int side = io::kMaxDecodedSide, std::int64_t pixels = io::kMaxImagePixelsPerFile) {
    return test::runBounded(memory, seconds, [&] {
        const PolygonMesh mesh = loadReference(file);
        std::int64_t total = 0;
        for (const Image& image : mesh.materials->images) {
            if (image.width > side || image.height > side)
                throw Error(image.name + " decoded at " + std::to_string(image.width) + " x " +
                            std::to_string(image.height));
            total += std::int64_t(image.width) * image.height;
        }
        if (total > pixels || total == 0) throw Error(std::to_string(total) + " pixels decoded");
    });
}

std::string base64(const std::string& bytes) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (size_t k = 0; k < bytes.size(); k += 3) {
        std::uint32_t v = std::uint32_t(std::uint8_t(bytes[k])) << 16;
        if (k + 1 < bytes.size()) v |= std::uint32_t(std::uint8_t(bytes[k + 1])) << 8;
        if (k + 2 < bytes.size()) v |= std::uint8_t(bytes[k + 2]);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += k + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
        out += k + 2 < bytes.size() ? digits[v & 63] : '=';
    }
    return out;
}

// One textured triangle (embedded buffer) whose materials each use one of `images` (URIs) as
// their base colour; `unused` images are listed but no texture names them.
std::string texturedGltf(const std::vector<std::string>& images, const std::vector<std::string>& unused = {},
                         const std::string& textureInfoExtra = "") {
    const float data[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    const std::string buffer = base64(std::string(reinterpret_cast<const char*>(data), sizeof data));
    std::string imageList, textures, materials, primitives;
    std::vector<std::string> all = images;
    all.insert(all.end(), unused.begin(), unused.end());
    for (size_t k = 0; k < all.size(); ++k) imageList += std::string(k ? "," : "") + R"({"uri":")" + all[k] + R"("})";
    for (size_t k = 0; k < images.size(); ++k) {
        textures += std::string(k ? "," : "") + R"({"source":)" + std::to_string(k) + "}";
        materials += std::string(k ? "," : "") + R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":)" +
                     std::to_string(k) + textureInfoExtra + "}}}";
        primitives += std::string(k ? "," : "") + R"({"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":)" +
                      std::to_string(k) + "}";
    }
    return R"({"asset":{"version":"2.0"},
  "buffers":[{"uri":"data:application/octet-stream;base64,)" +
           buffer + R"(","byteLength":60}],
  "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
               {"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],
  "images":[)" +
           imageList + R"(],"textures":[)" + textures + R"(],"materials":[)" + materials + R"(],
  "meshes":[{"primitives":[)" +
           primitives + R"(]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
}

TEST(HostileTextures, A16kPngBehindAnMtlMapIsRefusedOnItsHeader) {
    const fs::path dir = test::scratchDir("hostile_textures_mtl");
    writeText(dir / "bomb.png", bombPng(16384, 16384));
    writeText(dir / "m.mtl", "newmtl x\nmap_Kd bomb.png\n");
    writeText(dir / "m.obj",
              "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl x\nf 1/1 2/2 3/3\n");
    expectRefused(test::runBounded(256 * kMB, 20, [&] { loadReference(dir / "m.obj"); }), "bomb.png", "pixels");
}

TEST(HostileTextures, A16kPngAsAGltfImageOrDataUriIsRefusedOnItsHeader) {
    const fs::path dir = test::scratchDir("hostile_textures_gltf");
    writeText(dir / "bomb.png", bombPng(16384, 16384));
    writeText(dir / "file.gltf", texturedGltf({"bomb.png"}));
    expectRefused(test::runBounded(256 * kMB, 20, [&] { loadReference(dir / "file.gltf"); }), "file.gltf", "pixels");
    writeText(dir / "data.gltf", texturedGltf({"data:image/png;base64," + base64(bombPng(16384, 16384))}));
    expectRefused(test::runBounded(256 * kMB, 20, [&] { loadReference(dir / "data.gltf"); }), "data.gltf", "pixels");
}

// Six 8192 x 4096 images, each within any sensible per-image cap: together over the file's
// decoded-pixel budget, so each is decoded smaller, and the whole stays within it.
TEST(HostileTextures, ImagesTogetherAreDecodedSmallerToFitThePixelBudget) {
    const fs::path dir = test::scratchDir("hostile_textures_total");
    std::vector<std::string> names;
    for (char k : {'a', 'b', 'c', 'd', 'e', 'f'}) {
        names.push_back(std::string(1, k) + ".png");
        writeText(dir / names.back(), zeroPng(8192, 4096) + std::string(1, k));  // other bytes: not one image
    }
    writeText(dir / "six.gltf", texturedGltf(names));
    const auto outcome = loadWithinUse(dir / "six.gltf", 512 * kMB, 60);
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    EXPECT_EQ(outcome.error, "");
}

// The budget gives way down to kSmallestBudgetedSide a side, then refuses, naming the image.
TEST(HostileTextures, ThePixelBudgetRefusesAnImageItCannotFitEvenReduced) {
    io::PixelBudget budget(std::int64_t(300) * 300);
    EXPECT_EQ(budget.spend({8192, 8192, 4, false}, "a.png"), 28);  // 293², the largest that fits
    EXPECT_NE(test::errorMessage([&] {
                  budget.spend({8192, 8192, 4, false}, "b.png");
              }).find("b.png"),
              std::string::npos);
}

// Decompression bombs within the per-image cap: a 0.5 MB PNG of 11585² RGBA (537 MB decoded),
// its 16-bit twin (1 GB), behind an MTL map: decoded at 4096 a side, within 512 MB and seconds.
TEST(HostileTextures, APngBombWithinTheCapIsDecodedAtTheSizeSubdfitUses) {
    const fs::path dir = test::scratchDir("hostile_textures_png_bomb");
    for (int depth : {8, 16}) {
        writeText(dir / "bomb.png", zeroPng(11585, 11585, depth));
        writeTexturedObj(dir, "bomb.png");
        const auto outcome = loadWithinUse(dir / "m.obj", 512 * kMB, 30);
        ASSERT_TRUE(outcome.finished) << depth << " bits: " << outcome.problem;
        EXPECT_EQ(outcome.error, "") << depth << " bits";
    }
}

// A 12 KB JPEG whose frame says 11585²: decoded small by the JPEG's own DCT scaling, with one
// warning for its missing data; the same named by eight glTF images and five material slots is
// decoded once.
TEST(HostileTextures, AJpegClaimingAHugeFrameIsDecodedSmallAndOnce) {
    const fs::path dir = test::scratchDir("hostile_textures_jpeg_bomb");
    writeText(dir / "bomb.jpg", lyingJpeg(11585, 11585));
    writeTexturedObj(dir, "bomb.jpg");
    const auto one = loadWithinUse(dir / "m.obj", 384 * kMB, 20);
    ASSERT_TRUE(one.finished) << one.problem;
    EXPECT_EQ(one.error, "");

    std::string gltf = texturedGltf(std::vector<std::string>(8, "bomb.jpg"));
    for (int k = 0; k < 8; ++k) {  // each material names its texture in five slots
        const std::string index = R"({"index":)" + std::to_string(k) + "}";
        const std::string slot = R"("baseColorTexture":)" + index + "}";
        const size_t at = gltf.find(slot);
        ASSERT_NE(at, std::string::npos);
        gltf.replace(at, slot.size(),
                     R"("baseColorTexture":)" + index + R"(,"metallicRoughnessTexture":)" + index +
                         R"(},"normalTexture":)" + index + R"(,"occlusionTexture":)" + index +
                         R"(,"emissiveTexture":)" + index);
    }
    writeText(dir / "eight.gltf", gltf);
    const auto eight = loadWithinUse(dir / "eight.gltf", 384 * kMB, 20);
    ASSERT_TRUE(eight.finished) << eight.problem;
    EXPECT_EQ(eight.error, "");
}

// An EXR of 4000 channels (OpenImageIO would size its strips by them): refused on its header.
TEST(HostileTextures, AnImageOfThousandsOfChannelsIsRefusedNamingIt) {
    const fs::path dir = test::scratchDir("hostile_textures_channels");
    OIIO::ImageSpec spec(64, 64, 4000, OIIO::TypeDesc::HALF);
    spec.attribute("compression", "zip");
    const std::vector<std::uint16_t> zeros(std::size_t(64) * 64 * 4000, 0);
    auto out = OIIO::ImageOutput::create((dir / "many.exr").string());
    ASSERT_TRUE(out && out->open((dir / "many.exr").string(), spec) &&
                out->write_image(OIIO::TypeDesc::HALF, zeros.data()) && out->close());
    writeTexturedObj(dir, "many.exr");
    expectRefused(test::runBounded(256 * kMB, 20, [&] { loadReference(dir / "m.obj"); }), "many.exr", "4000 channels");
}

// A 35-byte GIF whose screen is 65535² and an interlaced PNG past what is decoded whole: refused
// on their headers, naming them (no library allocates what they state).
TEST(HostileTextures, AGifOrInterlacedPngClaimingTooMuchIsRefusedOnItsHeader) {
    const fs::path dir = test::scratchDir("hostile_textures_gif");
    writeText(dir / "huge.gif", std::string("GIF89a\xff\xff\xff\xff\x00\x00\x00", 13) + std::string(22, '\0'));
    writeTexturedObj(dir, "huge.gif");
    expectRefused(test::runBounded(256 * kMB, 10, [&] { loadReference(dir / "m.obj"); }), "huge.gif", "pixels");
    writeText(dir / "adam7.png", zeroPng(8192, 8192, 8, true));
    writeTexturedObj(dir, "adam7.png");
    expectRefused(test::runBounded(256 * kMB, 10, [&] { loadReference(dir / "m.obj"); }), "adam7.png", "interlaced");
}

// A PNG cut short: one line naming it, and nothing of libpng's on stderr before it.
TEST(HostileTextures, ATruncatedPngIsOneLineNamingIt) {
    const fs::path dir = test::scratchDir("hostile_textures_truncated");
    const std::string png = zeroPng(256, 256);
    writeText(dir / "cut.png", png.substr(0, png.size() / 2));
    writeTexturedObj(dir, "cut.png");
    const fs::path stderrFile = dir / "stderr.txt";
    const auto outcome = test::runBounded(256 * kMB, 10, [&] {
        const int fd = open(stderrFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
        dup2(fd, 2);
        close(fd);
        loadReference(dir / "m.obj");
    });
    expectRefused(outcome, "cut.png", "corrupt image");
    std::ifstream said(stderrFile);
    const std::string printed((std::istreambuf_iterator<char>(said)), std::istreambuf_iterator<char>());
    EXPECT_EQ(printed, "");
}

// Eight images naming one file are one image: decoded once, counted once.
TEST(HostileTextures, OneFileNamedByEightImagesIsDecodedOnce) {
    const fs::path dir = test::scratchDir("hostile_textures_eight");
    io::DecodedImage big{4096, 2048, std::vector<std::uint8_t>(4096 * 2048 * 4, 200)};
    const auto png = io::encodeImage(big, big.width, big.height, io::ImageFormat::Png);
    std::ofstream(dir / "big.png", std::ios::binary)
        .write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
    writeText(dir / "eight.gltf", texturedGltf(std::vector<std::string>(8, "big.png")));
    const auto outcome = test::runBounded(160 * kMB, 30, [&] {
        const PolygonMesh mesh = loadReference(dir / "eight.gltf");
        int decoded = 0, image = -1;
        for (const Image& i : mesh.materials->images) decoded += i.width > 0;
        for (const Material& m : mesh.materials->materials) {
            if (image < 0) image = m.baseColorTexture.image;
            if (m.baseColorTexture.image != image || image < 0) throw Error("the materials name different images");
        }
        if (decoded != 1) throw Error(std::to_string(decoded) + " images decoded");
    });
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    EXPECT_EQ(outcome.error, "");
}

TEST(HostileTextures, AnImageNoMaterialUsesIsNotDecoded) {
    const fs::path dir = test::scratchDir("hostile_textures_unused");
    io::writeImage(dir / "small.png", std::vector<glm::vec4>(4, {1, 0, 0, 1}), 2, 2);
    writeText(dir / "bomb.png", bombPng(16384, 16384));
    writeText(dir / "unused.gltf", texturedGltf({"small.png"}, {"bomb.png"}));
    const auto outcome = test::runBounded(256 * kMB, 20, [&] { loadReference(dir / "unused.gltf"); });
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    EXPECT_EQ(outcome.error, "");
}

// A progressive JPEG whose last scan repeats 150 times: each scan is a pass over the image, so past
// 100 it is refused, naming the file (an ordinary one has about ten).
TEST(HostileTextures, AProgressiveJpegOfEndlessScansIsRefused) {
    const fs::path dir = test::scratchDir("hostile_textures_scans");
    OIIO::ImageSpec spec(64, 64, 3, OIIO::TypeDesc::UINT8);
    spec.attribute("jpeg:progressive", 1);
    std::vector<std::uint8_t> pixels(64 * 64 * 3);
    for (size_t k = 0; k < pixels.size(); ++k) pixels[k] = std::uint8_t(k * 31);
    auto out = OIIO::ImageOutput::create((dir / "p.jpg").string());
    ASSERT_TRUE(out && out->open((dir / "p.jpg").string(), spec) &&
                out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close());
    std::ifstream in(dir / "p.jpg", std::ios::binary);
    const std::string jpeg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t lastScan = jpeg.rfind("\xff\xda"), end = jpeg.rfind("\xff\xd9");
    ASSERT_NE(lastScan, std::string::npos);
    std::string endless = jpeg.substr(0, end);
    for (int k = 0; k < 150; ++k) endless += jpeg.substr(lastScan, end - lastScan);
    writeText(dir / "endless.jpg", endless + "\xff\xd9");
    writeTexturedObj(dir, "endless.jpg");
    expectRefused(test::runBounded(256 * kMB, 10, [&] { loadReference(dir / "m.obj"); }), "endless.jpg",
                  "more than 100 scans");
}

// An image whose URI names no file: a warning naming it, and the surface renders without it.
TEST(HostileTextures, AMissingGltfImageIsAWarningNamingIt) {
    const fs::path dir = test::scratchDir("hostile_textures_missing");
    writeText(dir / "missing.gltf", texturedGltf({"nowhere.png"}));
    std::string said;
    const auto previous = setWarningSink([&](const std::string& w) { said += w + "\n"; });
    const PolygonMesh mesh = loadReference(dir / "missing.gltf");
    setWarningSink(previous);
    EXPECT_NE(said.find("nowhere.png"), std::string::npos) << said;
    EXPECT_NE(said.find("missing"), std::string::npos) << said;
    ASSERT_TRUE(mesh.materials);
    for (const Image& image : mesh.materials->images) EXPECT_EQ(image.width, 0);
}

// Offsets of 1e300 are infinite as floats; a texCoord of 1e30 is no set's index.
TEST(HostileTextures, TextureTransformsBeyondAnyFloatAreRefused) {
    const fs::path dir = test::scratchDir("hostile_textures_transform");
    io::writeImage(dir / "small.png", std::vector<glm::vec4>(4, {1, 0, 0, 1}), 2, 2);
    for (const auto& [name, extension] :
         std::vector<std::pair<std::string, std::string>>{{"offset.gltf", R"({"offset":[1e300,0]})"},
                                                          {"scale.gltf", R"({"scale":[1,-1e300]})"},
                                                          {"texcoord.gltf", R"({"texCoord":1e30})"}}) {
        writeText(dir / name,
                  texturedGltf({"small.png"}, {}, R"(,"extensions":{"KHR_texture_transform":)" + extension + "}"));
        std::string said;
        const auto previous = setWarningSink([&](const std::string& w) { said += w + "\n"; });
        said += test::errorMessage([&] { loadReference(dir / name); });
        setWarningSink(previous);
        EXPECT_NE(said.find(name), std::string::npos) << said;
        EXPECT_NE(said.find("KHR_texture_transform"), std::string::npos) << said;
        EXPECT_EQ(said.find("-2147483648"), std::string::npos) << said;
    }
}

}  // namespace
}  // namespace subdfit::mesh
