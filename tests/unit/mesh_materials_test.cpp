// A reference's appearance: glTF metallic-roughness materials with their images, samplers and
// KHR_texture_transform, and OBJ + MTL base colours; refusals name the file.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <tuple>
#include <vector>

#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "util/warnings.h"
#include "error_message.h"
#include "test_paths.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;
using test::errorMessage;

void writeText(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A 2 × 2 PNG: red, green / blue, white (top row first).
void writeCheckerPng(const fs::path& path) {
    // writeImage takes GL's bottom-up rows.
    io::writeImage(path, {{0, 0, 1, 1}, {1, 1, 1, 1}, {1, 0, 0, 1}, {0, 1, 0, 1}}, 2, 2);
}

TEST(MeshMaterials, TheDuckHasItsBaseColourTextureAndTextureCoordinates) {
    const PolygonMesh duck = loadReference(test::assetPath("gltf/Duck/Duck.glb"));
    ASSERT_TRUE(duck.materials);
    ASSERT_EQ(duck.materials->materials.size(), 1u);
    const Material& m = duck.materials->materials[0];
    EXPECT_EQ(m.metallicFactor, 0.0f);
    ASSERT_TRUE(m.baseColorTexture.present());
    const Image& image = duck.materials->images[size_t(m.baseColorTexture.image)];
    EXPECT_GT(image.width, 0);
    EXPECT_EQ(image.rgba.size(), size_t(image.width) * size_t(image.height) * 4);
    ASSERT_EQ(duck.uvs.size(), duck.positions.size());
    ASSERT_EQ(duck.faceMaterials.size(), size_t(duck.faceCount()));
    // The duck is yellow: the texture's mean is far more red than blue.
    double red = 0.0, blue = 0.0;
    for (size_t p = 0; p < image.rgba.size(); p += 4) red += image.rgba[p], blue += image.rgba[p + 2];
    EXPECT_GT(red, 1.5 * blue);
    for (const glm::vec2& uv : duck.uvs) EXPECT_TRUE(std::isfinite(uv.x) && std::isfinite(uv.y));
}

TEST(MeshMaterials, GeometryReadsSkipTheAppearance) {
    const PolygonMesh duck = loadMesh(test::assetPath("gltf/Duck/Duck.glb"));
    EXPECT_FALSE(duck.hasAppearance());
    EXPECT_TRUE(duck.uvs.empty());
    EXPECT_TRUE(duck.faceMaterials.empty());
}

TEST(MeshMaterials, TheWaterBottleHasEveryMetallicRoughnessTexture) {
    SUBDFIT_REQUIRE_SHARED(bottle, "gltf/WaterBottle/glTF/WaterBottle.gltf");
    const PolygonMesh mesh = loadReference(bottle);
    ASSERT_TRUE(mesh.materials);
    const Material& m = mesh.materials->materials.at(0);
    EXPECT_TRUE(m.baseColorTexture.present());
    EXPECT_TRUE(m.metallicRoughnessTexture.present());
    EXPECT_TRUE(m.normalTexture.present());
    EXPECT_TRUE(m.occlusionTexture.present());
    EXPECT_TRUE(m.emissiveTexture.present());
    EXPECT_EQ(m.emissiveFactor, glm::vec3(1.0f));
    EXPECT_EQ(mesh.materials->images.size(), 4u);
    for (const Image& image : mesh.materials->images) EXPECT_EQ(image.width, 2048) << image.name;
}

// A one-triangle glTF whose base colour texture has a sampler and a KHR_texture_transform.
std::string triangleGltf(const std::string& textureInfo, const std::string& imageUri,
                         const std::string& texture = R"({"source":0,"sampler":0})") {
    return R"({"asset":{"version":"2.0"},
  "buffers":[{"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/","byteLength":60}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":24}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5126,"count":3,"type":"VEC2"}],
  "images":[{"uri":")" +
           imageUri + R"("}],
  "samplers":[{"magFilter":9728,"wrapS":33071,"wrapT":33648}],
  "textures":[)" +
           texture + R"(],
  "materials":[{"pbrMetallicRoughness":{"baseColorTexture":)" +
           textureInfo + R"(,"roughnessFactor":0.25},
                "extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":4}},"emissiveFactor":[0.5,0,0]}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],
  "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
}

TEST(MeshMaterials, SamplersTextureTransformAndEmissiveStrengthAreRead) {
    const fs::path dir = test::scratchDir("materials_transform");
    writeCheckerPng(dir / "checker.png");
    writeText(
        dir / "t.gltf",
        triangleGltf(
            R"({"index":0,"extensions":{"KHR_texture_transform":{"offset":[0.5,0],"rotation":1.5707963,"scale":[2,1]}}})",
            "checker.png"));
    const PolygonMesh mesh = loadReference(dir / "t.gltf");
    ASSERT_TRUE(mesh.materials);
    const Material& m = mesh.materials->materials.at(0);
    EXPECT_FLOAT_EQ(m.roughnessFactor, 0.25f);
    EXPECT_FLOAT_EQ(m.emissiveFactor.x, 2.0f);  // 0.5 × strength 4
    const TextureRef& t = m.baseColorTexture;
    EXPECT_TRUE(t.nearest);
    EXPECT_EQ(t.wrapS, Wrap::ClampToEdge);
    EXPECT_EQ(t.wrapT, Wrap::MirroredRepeat);
    // Scale (2, 1), then a quarter turn (glTF's: u' = v, v' = −u in v-down terms), then the offset.
    const glm::vec3 moved = t.uvTransform * glm::vec3(1.0f, 0.0f, 1.0f);
    EXPECT_NEAR(moved.x, 0.5f, 1e-5f);
    EXPECT_NEAR(moved.y, -2.0f, 1e-5f);
    const Image& image = mesh.materials->images.at(0);
    ASSERT_EQ(image.width, 2);
    EXPECT_EQ(image.rgba[0], 255);  // top-left red
    EXPECT_EQ(image.rgba[1], 0);
    EXPECT_EQ(image.rgba[3 * 4 + 0], 255);  // bottom-right white
    EXPECT_EQ(mesh.uvs.size(), 3u);
}

// gltf-transform's `webp` writes textures whose only image is EXT_texture_webp's: read, not grey.
// A source only in an extension subdfit cannot decode (KTX2) is named in one warning.
TEST(MeshMaterials, AWebpOnlyTextureIsReadAndAnUndecodableOneIsNamed) {
    const fs::path dir = test::scratchDir("materials_webp");
    io::writeImage(dir / "red.webp", std::vector<glm::vec4>(4, {1, 0, 0, 1}), 2, 2);
    writeText(dir / "webp.gltf", triangleGltf(R"({"index":0})", "red.webp",
                                              R"({"sampler":0,"extensions":{"EXT_texture_webp":{"source":0}}})"));
    const PolygonMesh mesh = loadReference(dir / "webp.gltf");
    ASSERT_TRUE(mesh.materials);
    const TextureRef& t = mesh.materials->materials.at(0).baseColorTexture;
    ASSERT_TRUE(t.present());
    EXPECT_TRUE(t.nearest);  // the texture's own sampler still applies
    const Image& image = mesh.materials->images.at(size_t(t.image));
    ASSERT_EQ(image.width, 2);
    EXPECT_GT(image.rgba[0], 200);  // red, give or take WebP's loss
    EXPECT_LT(image.rgba[1], 60);

    writeText(dir / "ktx.gltf",
              triangleGltf(R"({"index":0})", "red.webp", R"({"extensions":{"KHR_texture_basisu":{"source":0}}})"));
    std::vector<std::string> warnings;
    const auto previous = setWarningSink([&](const std::string& w) { warnings.push_back(w); });
    const PolygonMesh untextured = loadReference(dir / "ktx.gltf");
    setWarningSink(previous);
    ASSERT_TRUE(untextured.materials);
    EXPECT_FALSE(untextured.materials->materials.at(0).baseColorTexture.present());
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("ktx.gltf"), std::string::npos) << warnings[0];
    EXPECT_NE(warnings[0].find("KHR_texture_basisu"), std::string::npos) << warnings[0];
}

TEST(MeshMaterials, ACorruptImageIsRefusedNamingTheFile) {
    const fs::path dir = test::scratchDir("materials_corrupt_image");
    writeText(dir / "broken.png", "\x89PNG\r\n\x1a\nnot really");
    writeText(dir / "t.gltf", triangleGltf(R"({"index":0})", "broken.png"));
    const std::string message = errorMessage([&] { loadReference(dir / "t.gltf"); });
    EXPECT_NE(message.find("t.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("broken.png"), std::string::npos) << message;
    // The geometry alone still loads: a cage never decodes images.
    EXPECT_NO_THROW(loadMesh(dir / "t.gltf"));
}

TEST(MeshMaterials, AnImageCutShortIsRefusedInOneLine) {
    const fs::path dir = test::scratchDir("materials_truncated_image");
    writeCheckerPng(dir / "whole.png");
    std::ifstream in(dir / "whole.png", std::ios::binary);
    const std::string whole{std::istreambuf_iterator<char>(in), {}};
    writeText(dir / "cut.png", whole.substr(0, whole.size() - 24));  // a header, its pixels cut short
    writeText(dir / "t.gltf", triangleGltf(R"({"index":0})", "cut.png"));
    const std::string message = errorMessage([&] { loadReference(dir / "t.gltf"); });
    EXPECT_NE(message.find("cut.png"), std::string::npos) << message;
    EXPECT_NE(message.find("corrupt image"), std::string::npos) << message;
    // The decoder's several lines, joined: neither a line break nor its escape.
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.find("\\x0A"), std::string::npos) << message;
}

TEST(MeshMaterials, ObjWithMtlHasItsBaseColourAndSplitsVerticesAtTextureSeams) {
    const fs::path dir = test::scratchDir("materials_obj");
    writeCheckerPng(dir / "checker.png");
    writeText(dir / "m.mtl",
              "newmtl painted\nKd 0.5 0.25 1\nNs 198\nmap_Kd checker.png\nillum 2\n\nnewmtl plain\nKd 0.2\n");
    // Two triangles sharing the edge 2-3, with different vt on one side of it.
    writeText(dir / "m.obj",
              "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
              "usemtl painted\nf 1/1 2/2 3/3\nusemtl plain\nf 1/5 3/3 4/4\n");
    const PolygonMesh mesh = loadReference(dir / "m.obj");
    ASSERT_TRUE(mesh.materials);
    EXPECT_EQ(mesh.vertexCount(), 5);  // vertex 1 appears with two texture coordinates
    ASSERT_EQ(mesh.uvs.size(), 5u);
    EXPECT_EQ(mesh.uvs[0], glm::vec2(0.0f, 1.0f));  // OBJ's v = 0 is the image's bottom row
    ASSERT_EQ(mesh.faceMaterials.size(), 2u);
    const Material& painted = mesh.materials->materials.at(size_t(mesh.faceMaterials[0]));
    const Material& plain = mesh.materials->materials.at(size_t(mesh.faceMaterials[1]));
    EXPECT_EQ(painted.name, "painted");
    EXPECT_EQ(painted.baseColorFactor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
    EXPECT_NEAR(painted.roughnessFactor, 0.1f, 1e-6f);
    EXPECT_TRUE(painted.baseColorTexture.present());
    EXPECT_EQ(plain.baseColorFactor, glm::vec4(0.2f, 0.2f, 0.2f, 1.0f));
    EXPECT_EQ(plain.metallicFactor, 0.0f);
    // The cage reading of the same file is untouched.
    EXPECT_EQ(loadMesh(dir / "m.obj").vertexCount(), 4);
}

TEST(MeshMaterials, AnMtlMapOutsideTheFolderIsRefused) {
    const fs::path dir = test::scratchDir("materials_obj_escape");
    writeText(dir / "m.mtl", "newmtl x\nmap_Kd ../../secret.png\n");
    writeText(dir / "m.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nusemtl x\nf 1 2 3\n");
    const std::string message = errorMessage([&] { loadReference(dir / "m.obj"); });
    EXPECT_NE(message.find("m.mtl: line 2"), std::string::npos) << message;
    EXPECT_NE(message.find("outside"), std::string::npos) << message;
}

// KHR_mesh_quantization lets texture coordinates be signed and not normalized (gltfpack -vt):
// read, as the extension defines them.
TEST(MeshMaterials, QuantizedTextureCoordinatesAreRead) {
    const fs::path dir = test::scratchDir("materials_quantized_uvs");
    writeCheckerPng(dir / "checker.png");
    for (const auto& [name, normalized, expected] : std::vector<std::tuple<std::string, bool, float>>{
             {"signed_normalized.gltf", true, -1.0f}, {"signed.gltf", false, -32767.0f}}) {
        writeText(dir / name, std::string(R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_mesh_quantization"],
  "buffers":[{"uri":"data:application/octet-stream;base64,BASE64","byteLength":48}],
  "bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":12}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
               {"bufferView":1,"componentType":5122,"normalized":NORMALIZED,"count":3,"type":"VEC2"}],
  "images":[{"uri":"checker.png"}],"textures":[{"source":0}],
  "materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"material":0}]}],
  "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})"));
        std::string text;
        {
            std::ifstream in(dir / name);
            text.assign(std::istreambuf_iterator<char>(in), {});
        }
        text.replace(text.find("BASE64"), 6, "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAP9/AAABgABA");
        text.replace(text.find("NORMALIZED"), 10, normalized ? "true" : "false");
        writeText(dir / name, text);
        const PolygonMesh mesh = loadReference(dir / name);
        ASSERT_EQ(mesh.uvs.size(), 3u) << name;
        EXPECT_NEAR(mesh.uvs[2].x, expected, 1e-6f) << name;
    }
}

}  // namespace
}  // namespace subdfit::mesh
