// `subdfit decode` for engines: quantised, meshopt-compressed glTF that reads back as the float
// surface; a chain of levels whose distance to level 0 rises as their triangles fall, described
// in a JSON, priced whole before it starts and written all together or not at all; the coarsest
// density within an error bound, one below what the surface resolves clamped; bad bounds refused.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "common/error_bound.h"
#include "error_message.h"
#include "export/engine/engine_decode.h"
#include "export/engine/error_density.h"
#include "export/engine/surface_error.h"
#include "export/gltf/meshopt_encoding.h"
#include "export/engine/subd_decode.h"
#include "export/gltf/surface_glb.h"
#include "geometry/surface_distance.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "noisy_heights.h"
#include "test_paths.h"
#include "util/warnings.h"

namespace subdfit::exporter {
namespace {

namespace fs = std::filesystem;

// A lumpy sphere: heights on 4-cell tiles, so that coarser densities do lose detail.
codec::SubdAsset lumpySphere(std::uint32_t decodeTriangles, int n = 4) {
    return test::noisyHeightsSphere(n, 0.04f, 3, decodeTriangles);
}

nlohmann::json glbJson(const fs::path& path) {
    std::ifstream file(path, std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.begin() + 20, bytes.begin() + 20 + length);
}

TEST(EngineDecode, MeshoptOutputReadsBackAsTheFloatSurfaceWithinItsQuantisation) {
    const auto dir = test::scratchDir("engine_decode_meshopt");
    codec::writeSubd(dir / "asset.subd", lumpySphere(20000));
    const auto compact = decodeToGlb(dir / "asset.subd", dir / "compact.glb", {}, MeshCoding::Meshopt);
    const auto plain = decodeToGlb(dir / "asset.subd", dir / "plain.glb", {}, MeshCoding::Float);
    EXPECT_LT(compact.bytes * 3, plain.bytes);  // positions, normals, tangents, texcoords packed
    const nlohmann::json doc = glbJson(dir / "compact.glb");
    EXPECT_EQ(doc["extensionsRequired"], nlohmann::json({"EXT_meshopt_compression", "KHR_mesh_quantization"}));
    EXPECT_EQ(doc["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"], true);
    const int position = doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
    EXPECT_EQ(doc["accessors"][position]["componentType"], 5123);

    const mesh::PolygonMesh a = mesh::loadMesh(dir / "compact.glb"), b = mesh::loadMesh(dir / "plain.glb");
    ASSERT_EQ(a.faceCount(), b.faceCount());
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : b.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float step = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / float((1 << kQuantisedPositionBits) - 1);
    const auto d = geometry::surfaceDistance(a, b, 20000);
    EXPECT_LE(d.hausdorff, double(step));  // half a step per axis, at most
    EXPECT_GT(d.hausdorff, 0.0);           // and it is quantised
}

// The default: KHR_mesh_quantization alone, which every glTF reader opens with no decoder set (as
// Blender's importer and three's GLTFLoader do): plain views, 14-bit positions, normals as bytes,
// no material, texture coordinates or tangents for a surface that has no image.
TEST(EngineDecode, TheDefaultIsQuantisedWithNoDecoderNeeded) {
    const auto dir = test::scratchDir("engine_decode_quantized");
    codec::writeSubd(dir / "asset.subd", lumpySphere(20000));
    const auto quantized = decodeToGlb(dir / "asset.subd", dir / "quantized.glb");
    const auto plain = decodeToGlb(dir / "asset.subd", dir / "plain.glb", {}, MeshCoding::Float);
    EXPECT_LT(quantized.bytes * 2, plain.bytes);
    const nlohmann::json doc = glbJson(dir / "quantized.glb");
    EXPECT_EQ(doc["extensionsRequired"], nlohmann::json({"KHR_mesh_quantization"}));
    EXPECT_EQ(doc["buffers"].size(), 1u);
    for (const auto& view : doc["bufferViews"]) EXPECT_FALSE(view.contains("extensions"));
    const auto& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
    EXPECT_EQ(doc["accessors"][attributes["POSITION"].get<int>()]["componentType"], 5123);
    EXPECT_EQ(doc["accessors"][attributes["NORMAL"].get<int>()]["componentType"], 5120);
    EXPECT_FALSE(attributes.contains("TEXCOORD_0"));
    EXPECT_FALSE(attributes.contains("TANGENT"));
    EXPECT_FALSE(doc.contains("materials"));
    for (const char* name : {"plain.glb"}) {
        const nlohmann::json floats = glbJson(dir / name);
        EXPECT_FALSE(floats.contains("materials")) << name;  // no grey invented for a reference that had none
        EXPECT_FALSE(floats["meshes"][0]["primitives"][0]["attributes"].contains("TEXCOORD_0")) << name;
    }
    const mesh::PolygonMesh a = mesh::loadMesh(dir / "quantized.glb"), b = mesh::loadMesh(dir / "plain.glb");
    ASSERT_EQ(a.faceCount(), b.faceCount());
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : b.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float step = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / float((1 << kQuantisedPositionBits) - 1);
    EXPECT_LE(geometry::surfaceDistance(a, b, 20000).hausdorff, double(step));
}

// Normals ship in the octahedral filter and read back (through meshoptimizer's decoder, as
// engines' do) within a degree or two of the float file's at the same point.
TEST(EngineDecode, OctahedralNormalsReadBackAsTheFloatOnes) {
    const auto dir = test::scratchDir("engine_decode_normals");
    codec::writeSubd(dir / "asset.subd", lumpySphere(3000));
    decodeForEngines(dir / "asset.subd", dir / "compact.glb", EngineDecodeOptions{.coding = MeshCoding::Meshopt});
    decodeToGlb(dir / "asset.subd", dir / "plain.glb", {}, MeshCoding::Float);
    const nlohmann::json doc = glbJson(dir / "compact.glb");
    const int normal = doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"];
    const int view = doc["accessors"][normal]["bufferView"];
    EXPECT_EQ(doc["bufferViews"][view]["extensions"]["EXT_meshopt_compression"]["filter"], "OCTAHEDRAL");

    const mesh::PolygonMesh a = mesh::loadReference(dir / "compact.glb"), b = mesh::loadReference(dir / "plain.glb");
    ASSERT_EQ(a.normals.size(), a.positions.size());
    ASSERT_EQ(b.normals.size(), b.positions.size());
    EXPECT_LT(a.positions.size(), b.positions.size());  // without texture coordinates, face borders' twins merge
    const float near = 1e-3f, cosLimit = std::cos(glm::radians(2.0f));
    int far = 0;
    for (size_t v = 0; v < a.positions.size(); ++v) {
        float best = -1.0f;
        for (size_t u = 0; u < b.positions.size(); ++u)
            if (glm::distance(a.positions[v], b.positions[u]) < near)
                best = std::max(best, glm::dot(a.normals[v], b.normals[u]));
        far += best < cosLimit;
    }
    EXPECT_EQ(far, 0);
}

TEST(EngineDecode, ThreeLevelsWhoseErrorsRiseAsTheirTrianglesFall) {
    const auto dir = test::scratchDir("engine_decode_lods");
    codec::writeSubd(dir / "asset.subd", lumpySphere(40000));
    const auto written = decodeForEngines(dir / "asset.subd", dir / "lumpy.glb", {.lods = 3});
    ASSERT_EQ(written.size(), 4u);  // three .glb and the JSON
    for (const char* name : {"lumpy.glb", "lumpy_lod1.glb", "lumpy_lod2.glb", "lumpy_lods.json"})
        EXPECT_TRUE(fs::exists(dir / name)) << name;
    std::ifstream file(dir / "lumpy_lods.json");
    const nlohmann::json doc = nlohmann::json::parse(file);
    const auto& lods = doc["lods"];
    ASSERT_EQ(lods.size(), 3u);
    EXPECT_EQ(lods[0]["max_distance"], 0.0);
    EXPECT_EQ(lods[0]["screen_size"], 1.0);
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(mesh::loadMesh(dir / lods[k]["file"].get<std::string>()).faceCount(),
                  lods[k]["triangles"].get<int>());
        EXPECT_EQ(fs::file_size(dir / lods[k]["file"].get<std::string>()), lods[k]["bytes"].get<std::uintmax_t>());
        // Heights alone ship no image, so nothing reads texture coordinates or tangents.
        const nlohmann::json level = glbJson(dir / lods[k]["file"].get<std::string>());
        const auto& attributes = level["meshes"][0]["primitives"][0]["attributes"];
        EXPECT_TRUE(attributes.contains("NORMAL"));
        EXPECT_FALSE(attributes.contains("TEXCOORD_0"));
        EXPECT_FALSE(attributes.contains("TANGENT"));
        if (k == 0) continue;
        EXPECT_LT(lods[k]["triangles"].get<int>(), lods[k - 1]["triangles"].get<int>());
        EXPECT_LE(lods[k]["triangles"].get<int>(), lods[k - 1]["triangles"].get<int>() / 2 + 1);
        EXPECT_GT(lods[k]["mean_distance"].get<double>(), lods[k - 1]["mean_distance"].get<double>());
        EXPECT_GT(lods[k]["max_distance"].get<double>(), lods[k - 1]["max_distance"].get<double>());
        EXPECT_LT(lods[k]["screen_size"].get<double>(), lods[k - 1]["screen_size"].get<double>());
        EXPECT_LT(lods[k]["bytes"].get<std::uintmax_t>(), lods[k - 1]["bytes"].get<std::uintmax_t>());
    }
    // By default level 0 follows the recorded reference count, within twice.
    EXPECT_GE(lods[0]["triangles"].get<int>(), 20000);
    EXPECT_LE(lods[0]["triangles"].get<int>(), 80000);
}

// The density --max-error picks is within the bound of the reference tessellation, and one
// segment fewer is not.
TEST(EngineDecode, MaxErrorChoosesTheCoarsestDensityWithinTheBound) {
    const codec::SubdAsset asset = lumpySphere(0, 2);  // 24 quads: a reference of 64 segments stays small
    codec::DecodeBudget budget("lumpy.subd");
    const ErrorDensity within = densityWithin(asset, {.value = 0.004, .ofDiagonal = false}, budget);
    EXPECT_LE(within.maxDistance, 0.004);
    ASSERT_GT(within.density.segments, 1);
    ASSERT_LT(within.density.segments, within.referenceSegments);
    const auto fine = surface::triangleMesh(surface::tessellate(asset.cage, asset.maps, within.referenceSegments));
    const auto coarser =
        surface::triangleMesh(surface::tessellate(asset.cage, asset.maps, within.density.segments - 1));
    EXPECT_GT(geometry::surfaceDistance(coarser, fine, kErrorSamples).hausdorff, 0.004);
    // A tighter bound asks for more segments; as a fraction of the diagonal, the same rule.
    codec::DecodeBudget again("lumpy.subd");
    EXPECT_GT(densityWithin(asset, {.value = 0.001, .ofDiagonal = false}, again).density.segments,
              within.density.segments);
    codec::DecodeBudget relative("lumpy.subd");
    const ErrorDensity percent = densityWithin(asset, {.value = 0.001, .ofDiagonal = true}, relative);
    EXPECT_LE(percent.maxDistance, percent.bound);
    EXPECT_GT(percent.bound, 0.001);  // the sphere's diagonal is over 1
}

// A file whose header asks for 4M triangles: one level takes them; a chain of eight is priced
// whole first (level 0, its BVH, the simplifier's input, the candidates), so the default level 0
// gives way to what the budget holds, and an asked-for density that would pass it is refused.
TEST(EngineDecode, AChainOfLevelsIsPricedWholeBeforeItStarts) {
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(100);
    const codec::SubdOutline outline{.cage = cage, .decodeTriangles = 1u << 22};
    codec::DecodeBudget one("one.subd"), chain("chain.subd"), asked("asked.subd");
    const codec::DecodeDensity single = codec::pricedDensity(outline, {}, one);
    const codec::DecodeDensity eight = codec::pricedDensity(outline, {}, chain, 8);
    EXPECT_GT(single.triangles, 3'000'000);
    EXPECT_LT(eight.triangles, single.triangles);
    EXPECT_LE(decodeOutputBytes(eight) + lodChainBytes(eight, 8), codec::kDecodeBudgetBytes);
    const std::string refusal =
        test::errorMessage([&] { codec::pricedDensity(outline, {.triangles = 4'000'000}, asked, 8); });
    EXPECT_NE(refusal.find("asked.subd"), std::string::npos) << refusal;
    EXPECT_NE(refusal.find("8 levels of detail"), std::string::npos) << refusal;
}

// A chain whose last file cannot be written (its name past the 255 bytes a file name may have)
// writes none of them; an input name that is not UTF-8 reaches the JSON replaced, not as an error.
TEST(EngineDecode, TheLevelsAreWrittenTogetherOrNotAtAll) {
    const auto dir = test::scratchDir("engine_decode_together");
    codec::writeSubd(dir / "asset.subd", lumpySphere(2000, 2));
    const std::string stem(246, 'a');  // stem_lod1.glb fits; stem_lods.json does not
    const std::string refusal =
        test::errorMessage([&] { decodeForEngines(dir / "asset.subd", dir / (stem + ".glb"), {.lods = 2}); });
    EXPECT_NE(refusal.find("bytes, more than the 255"), std::string::npos) << refusal;
    EXPECT_TRUE(fs::is_empty(dir / "") || (fs::directory_iterator(dir)->path().filename() == "asset.subd" &&
                                           std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1));

    const fs::path latin1 = dir / "caf\xe9.subd";
    fs::copy_file(dir / "asset.subd", latin1);
    const auto written = decodeForEngines(latin1, dir / "cafe.glb", {.lods = 2});
    ASSERT_EQ(written.size(), 3u);
    std::ifstream file(dir / "cafe_lods.json");
    const nlohmann::json doc = nlohmann::json::parse(file);
    EXPECT_EQ(doc["asset"].get<std::string>(), "caf\xef\xbf\xbd.subd");  // U+FFFD
}

// 1e-30 % of the diagonal is no distance floats resolve: the finest density at once, said so.
TEST(EngineDecode, AnErrorBoundBelowWhatTheSurfaceResolvesIsClampedToTheFinest) {
    const auto dir = test::scratchDir("engine_decode_tiny_bound");
    codec::writeSubd(dir / "asset.subd", lumpySphere(2000, 2));
    std::string said;
    const WarningSink previous = setWarningSink([&](const std::string& w) { said += w + "\n"; });
    decodeForEngines(dir / "asset.subd", dir / "fine.glb",
                     {.maxError = ErrorBound{.value = 1e-32, .ofDiagonal = true}, .lods = 1});
    setWarningSink(previous);
    EXPECT_NE(said.find("below what the surface resolves"), std::string::npos) << said;
    std::ifstream file(dir / "fine_lods.json");
    const nlohmann::json doc = nlohmann::json::parse(file);
    EXPECT_TRUE(doc["max_error"]["clamped_to_finest"].get<bool>());
    EXPECT_EQ(doc["lods"][0]["segments"], doc["max_error"]["reference_segments"]);
}

TEST(EngineDecode, BadErrorBoundsAndLevelCountsAreRefused) {
    std::string problem;
    EXPECT_EQ(apps::parseErrorBound("0.002", problem)->value, 0.002);
    EXPECT_TRUE(apps::parseErrorBound("0.5%", problem)->ofDiagonal);
    EXPECT_DOUBLE_EQ(apps::parseErrorBound("0.5%", problem)->value, 0.005);
    for (const char* text : {"0", "-1", "abc", "1%%", "%", "", " 1", "1e400", "nan", "inf", "2mm"}) {
        EXPECT_FALSE(apps::parseErrorBound(text, problem)) << text;
        EXPECT_NE(problem.find("must be a positive distance"), std::string::npos);
    }
    const auto dir = test::scratchDir("engine_decode_bad");
    codec::writeSubd(dir / "asset.subd", lumpySphere(1000));
    EXPECT_THROW(decodeForEngines(dir / "asset.subd", dir / "x.glb", {.maxError = ErrorBound{.value = 0.0}}),
                 OptionError);
    EXPECT_THROW(decodeForEngines(dir / "asset.subd", dir / "x.glb", {.lods = kMostLods + 1}), OptionError);
    EXPECT_FALSE(fs::exists(dir / "x.glb"));
}

}  // namespace
}  // namespace subdfit::exporter
