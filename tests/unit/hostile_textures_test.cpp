// Images made to cost what a reference does not need: a PNG whose header promises 16384² pixels
// (behind an MTL map, a glTF image, a data: URI), several that together pass any per-image cap,
// one file named by eight images, an image no material uses; and KHR_texture_transform numbers
// beyond any float. Each image's header is read first: refused in one line naming the file, or
// decoded once, inside a child process with a memory limit (support/bounded_run.h).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

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
  "buffers":[{"uri":"data:application/octet-stream;base64,)" + buffer + R"(","byteLength":60}],
  "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
               {"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],
  "images":[)" + imageList + R"(],"textures":[)" + textures + R"(],"materials":[)" + materials + R"(],
  "meshes":[{"primitives":[)" + primitives + R"(]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
}

TEST(HostileTextures, A16kPngBehindAnMtlMapIsRefusedOnItsHeader) {
    const fs::path dir = test::scratchDir("hostile_textures_mtl");
    writeText(dir / "bomb.png", bombPng(16384, 16384));
    writeText(dir / "m.mtl", "newmtl x\nmap_Kd bomb.png\n");
    writeText(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl x\nf 1/1 2/2 3/3\n");
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

// Three 8192² images, each within any sensible per-image cap: together over the run's budget.
TEST(HostileTextures, ImagesTogetherMayNotExceedThePixelBudget) {
    const fs::path dir = test::scratchDir("hostile_textures_total");
    for (char k : {'a', 'b', 'c'}) writeText(dir / (std::string(1, k) + ".png"), bombPng(8192, 8192, k));
    writeText(dir / "three.gltf", texturedGltf({"a.png", "b.png", "c.png"}));
    expectRefused(test::runBounded(192 * kMB, 20, [&] { loadReference(dir / "three.gltf"); }), "three.gltf", "pixels");
}

// Eight images naming one file are one image: decoded once, counted once.
TEST(HostileTextures, OneFileNamedByEightImagesIsDecodedOnce) {
    const fs::path dir = test::scratchDir("hostile_textures_eight");
    io::DecodedImage big{4096, 2048, std::vector<std::uint8_t>(4096 * 2048 * 4, 200)};
    const auto png = io::encodeImage(big, big.width, big.height, io::ImageFormat::Png);
    std::ofstream(dir / "big.png", std::ios::binary).write(reinterpret_cast<const char*>(png.data()), std::streamsize(png.size()));
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

// Offsets of 1e300 are infinite as floats; a texCoord of 1e30 is no set's index.
TEST(HostileTextures, TextureTransformsBeyondAnyFloatAreRefused) {
    const fs::path dir = test::scratchDir("hostile_textures_transform");
    io::writeImage(dir / "small.png", std::vector<glm::vec4>(4, {1, 0, 0, 1}), 2, 2);
    for (const auto& [name, extension] : std::vector<std::pair<std::string, std::string>>{
             {"offset.gltf", R"({"offset":[1e300,0]})"},
             {"scale.gltf", R"({"scale":[1,-1e300]})"},
             {"texcoord.gltf", R"({"texCoord":1e30})"}}) {
        writeText(dir / name, texturedGltf({"small.png"}, {}, R"(,"extensions":{"KHR_texture_transform":)" + extension + "}"));
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
