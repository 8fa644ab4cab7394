// The fitted asset as glTF: the displaced limit tessellation (finite, outward, displaced by the
// map), and the plain and Draco GLBs read back through our own glTF reader.
#include <gtest/gtest.h>

#include <draco/compression/decode.h>

#include <cmath>
#include <cstring>
#include <algorithm>
#include <fstream>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "export/gltf/glb_writer.h"
#include "export/gltf_mesh.h"
#include "codec/map_atlas.h"
#include "export/map_images.h"
#include "io/input_file.h"
#include "mesh/gltf_reader.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr float kHeight = 0.1f;

// A quad-sphere cage, T = 4, a constant displacement and a normal map that varies per node.
struct Asset {
    mesh::PolygonMesh cage = mesh::makeQuadSphere(4);
    surface::SurfaceMaps maps;

    Asset() {
        maps.layout = surface::buildTexelLayout(cage, 4);
        maps.displacement.assign(size_t(maps.layout.nodeCount), kHeight);
        for (int n = 0; n < maps.layout.nodeCount; ++n) {
            maps.normal.push_back(0.5f * std::sin(0.37f * float(n)));
            maps.normal.push_back(0.3f * std::cos(0.91f * float(n)));
        }
    }
};

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
};

Bounds bounds(const std::vector<glm::vec3>& points) {
    Bounds b;
    for (const glm::vec3& p : points) b.lo = glm::min(b.lo, p), b.hi = glm::max(b.hi, p);
    return b;
}

bool finite(std::span<const float> values) {
    for (float v : values)
        if (!std::isfinite(v)) return false;
    return true;
}

template <typename Vec>
std::span<const float> floats(const std::vector<Vec>& v) {
    return {&v[0][0], v.size() * sizeof(Vec) / sizeof(float)};
}

// What fitted.glb encodes: the displaced limit surface's tessellation with atlas texcoords.
GltfMesh fittedMesh(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps, int segments) {
    return gltfMesh(surface::tessellate(cage, maps, segments), codec::atlasLayout(maps.layout));
}

void expectWellFormed(const GltfMesh& tess) {
    ASSERT_GT(tess.vertexCount(), 0u);
    EXPECT_TRUE(finite(floats(tess.positions)));
    EXPECT_TRUE(finite(floats(tess.normals)));
    EXPECT_TRUE(finite(floats(tess.tangents)));
    EXPECT_TRUE(finite(floats(tess.uvs)));
    for (size_t v = 0; v < tess.vertexCount(); ++v) {
        const glm::vec3 n = tess.normals[v], t = glm::vec3(tess.tangents[v]);
        ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f) << v;
        ASSERT_NEAR(glm::length(t), 1.0f, 1e-4f) << v;
        ASSERT_NEAR(glm::dot(n, t), 0.0f, 1e-4f) << v;
        ASSERT_EQ(std::abs(tess.tangents[v].w), 1.0f) << v;
        ASSERT_TRUE(tess.uvs[v].x >= 0 && tess.uvs[v].x <= 1 && tess.uvs[v].y >= 0 && tess.uvs[v].y <= 1) << v;
    }
    for (uint32_t i : tess.indices) ASSERT_LT(i, tess.vertexCount());
}

// Every triangle of a closed surface around the origin faces away from it.
void expectOutward(const GltfMesh& tess) {
    for (size_t t = 0; t < tess.triangleCount(); ++t) {
        const glm::vec3 a = tess.positions[tess.indices[3 * t]], b = tess.positions[tess.indices[3 * t + 1]],
                        c = tess.positions[tess.indices[3 * t + 2]];
        const glm::vec3 facing = glm::cross(b - a, c - a);
        ASSERT_GT(glm::dot(facing, a + b + c), 0.0f) << "triangle " << t;
        ASSERT_GT(glm::dot(facing, tess.normals[tess.indices[3 * t]]), 0.0f) << "triangle " << t;
    }
}

struct Glb {
    json document;
    std::string binary;
};

// Our own reading of the container, checked against spec 4.4 byte for byte.
Glb readGlb(const fs::path& path) {
    const std::string bytes = io::readInputFile(path);
    auto u32 = [&](size_t offset) {
        uint32_t v;
        std::memcpy(&v, bytes.data() + offset, 4);
        return v;
    };
    EXPECT_EQ(bytes.substr(0, 4), "glTF");
    EXPECT_EQ(u32(4), 2u);
    EXPECT_EQ(u32(8), bytes.size());
    const uint32_t jsonLength = u32(12);
    EXPECT_EQ(jsonLength % 4, 0u);
    EXPECT_EQ(u32(16), 0x4E4F534Au);
    Glb glb{json::parse(bytes.substr(20, jsonLength)), {}};
    const size_t bin = 20 + jsonLength;
    if (bin < bytes.size()) {
        EXPECT_EQ(u32(bin + 4), 0x004E4942u);
        EXPECT_EQ(u32(bin) % 4, 0u);
        EXPECT_EQ(bin + 8 + u32(bin), bytes.size());
        glb.binary = bytes.substr(bin + 8, u32(bin));
    }
    return glb;
}

std::string viewBytes(const Glb& glb, int view) {
    const json& v = glb.document["bufferViews"][view];
    return glb.binary.substr(v.value("byteOffset", size_t(0)), v["byteLength"].get<size_t>());
}

class ExportGlb : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        asset_ = new Asset;
        tess_ = new GltfMesh(fittedMesh(asset_->cage, asset_->maps, 8));
        png_ = new std::vector<unsigned char>(encodeNormalPng(codec::atlasLayout(asset_->maps.layout), asset_->maps));
        dir_ = new fs::path(test::scratchDir("export_glb"));
        plain_ = new io::WrittenFile(writeFittedGlb(*dir_ / "fitted.glb", *tess_, *png_, false));
        draco_ = new io::WrittenFile(writeFittedGlb(*dir_ / "fitted_draco.glb", *tess_, *png_, true));
    }
    static void TearDownTestSuite() {
        delete asset_, delete tess_, delete png_, delete dir_, delete plain_, delete draco_;
    }
    static inline Asset* asset_ = nullptr;
    static inline GltfMesh* tess_ = nullptr;
    static inline std::vector<unsigned char>* png_ = nullptr;
    static inline fs::path* dir_ = nullptr;
    static inline io::WrittenFile *plain_ = nullptr, *draco_ = nullptr;
};

TEST_F(ExportGlb, TessellationIsFiniteUnitAndOutward) {
    EXPECT_EQ(tess_->vertexCount(), 96u * 9 * 9);
    EXPECT_EQ(tess_->triangleCount(), 96u * 8 * 8 * 2);
    EXPECT_EQ(tess_->atlasSize, glm::ivec2(50, 50));
    expectWellFormed(*tess_);
    expectOutward(*tess_);
    for (size_t v = 0; v < tess_->vertexCount(); ++v)
        ASSERT_EQ(tess_->tangents[v].w, 1.0f) << "the ptex frame is right-handed about the outward normal";
}

TEST_F(ExportGlb, ConstantDisplacementMovesTheLimitSurfaceOutByTheHeight) {
    surface::SurfaceMaps flat = asset_->maps;
    flat.displacement.clear();
    const GltfMesh limit = fittedMesh(asset_->cage, flat, 8);
    expectWellFormed(limit);
    const Bounds before = bounds(limit.positions), after = bounds(tess_->positions);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(after.hi[axis], before.hi[axis] + kHeight, 1e-4f) << axis;
        EXPECT_NEAR(after.lo[axis], before.lo[axis] - kHeight, 1e-4f) << axis;
    }
    for (size_t v = 0; v < limit.vertexCount(); ++v) {
        ASSERT_NEAR(glm::distance(tess_->positions[v], limit.positions[v]), kHeight, 1e-5f) << v;
        // A constant height on a smooth surface keeps its normal.
        ASSERT_GT(glm::dot(tess_->normals[v], limit.normals[v]), 0.9999f) << v;
    }
    std::cout << "limit radius (max x) " << before.hi.x << ", displaced " << after.hi.x << "\n";
}

TEST_F(ExportGlb, PlainGlbReadsBackWithEveryVertex) {
    const mesh::PolygonMesh read = mesh::readGltf(plain_->path);
    EXPECT_EQ(size_t(read.vertexCount()), tess_->vertexCount());
    EXPECT_EQ(size_t(read.faceCount()), tess_->triangleCount());
    EXPECT_EQ(read.positions, tess_->positions);
    EXPECT_EQ(read.faceIndices, std::vector<int>(tess_->indices.begin(), tess_->indices.end()));

    const Glb glb = readGlb(plain_->path);
    const json& doc = glb.document;
    EXPECT_EQ(doc["asset"]["version"], "2.0");
    EXPECT_EQ(doc["asset"]["generator"], "subdfit");
    EXPECT_FALSE(doc.contains("extensionsUsed"));
    const json& primitive = doc["meshes"][0]["primitives"][0];
    const json& position = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
    const Bounds b = bounds(tess_->positions);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_EQ(position["min"][axis].get<float>(), b.lo[axis]);
        EXPECT_EQ(position["max"][axis].get<float>(), b.hi[axis]);
    }
    for (const char* name : {"POSITION", "NORMAL", "TANGENT", "TEXCOORD_0"}) {
        const json& a = doc["accessors"][primitive["attributes"][name].get<int>()];
        EXPECT_EQ(a["count"], tess_->vertexCount()) << name;
        const std::string data = viewBytes(glb, a["bufferView"]);
        std::vector<float> values(data.size() / 4);
        std::memcpy(values.data(), data.data(), data.size());
        EXPECT_TRUE(finite(values)) << name;
    }
    const json& material = doc["materials"][0];
    EXPECT_EQ(material["pbrMetallicRoughness"]["metallicFactor"], 0.0);
    EXPECT_EQ(material["pbrMetallicRoughness"]["roughnessFactor"], 0.5);  // the default surface a normal map sits on
    const int image = doc["textures"][material["normalTexture"]["index"].get<int>()]["source"];
    EXPECT_EQ(doc["images"][image]["mimeType"], "image/png");
    const std::string png = viewBytes(glb, doc["images"][image]["bufferView"]);
    EXPECT_EQ(png, std::string(png_->begin(), png_->end()));
}

TEST_F(ExportGlb, DracoGlbIsSmallerAndDecodesToTheSameSurface) {
    std::cout << "plain " << plain_->bytes << " bytes, Draco " << draco_->bytes << " bytes (" << tess_->vertexCount()
              << " vertices, " << tess_->triangleCount() << " triangles, PNG " << png_->size() << " bytes)\n";
    EXPECT_LT(draco_->bytes, plain_->bytes);

    const mesh::PolygonMesh read = mesh::readGltf(draco_->path);
    EXPECT_EQ(size_t(read.faceCount()), tess_->triangleCount());
    const Bounds expected = bounds(tess_->positions), got = bounds(read.positions);
    // 14 bits over the ~2.2 wide box: a step of ~1.4e-4.
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(got.lo[axis], expected.lo[axis], 2e-4f) << axis;
        EXPECT_NEAR(got.hi[axis], expected.hi[axis], 2e-4f) << axis;
    }

    const Glb glb = readGlb(draco_->path);
    const json& doc = glb.document;
    EXPECT_EQ(doc["extensionsUsed"], json::array({"KHR_draco_mesh_compression"}));
    EXPECT_EQ(doc["extensionsRequired"], json::array({"KHR_draco_mesh_compression"}));
    const json& primitive = doc["meshes"][0]["primitives"][0];
    for (const json& a : doc["accessors"]) EXPECT_FALSE(a.contains("bufferView"));
    const json& position = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
    for (int axis = 0; axis < 3; ++axis) {  // min/max describe the decoded positions
        EXPECT_EQ(position["min"][axis].get<float>(), got.lo[axis]);
        EXPECT_EQ(position["max"][axis].get<float>(), got.hi[axis]);
    }

    // Every attribute decodes finite, with the count the accessors state.
    const json& extension = primitive["extensions"]["KHR_draco_mesh_compression"];
    const std::string payload = viewBytes(glb, extension["bufferView"]);
    draco::DecoderBuffer buffer;
    buffer.Init(payload.data(), payload.size());
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    ASSERT_TRUE(decoded.ok());
    const draco::Mesh& dm = *decoded.value();
    EXPECT_EQ(dm.num_points(), position["count"].get<uint32_t>());
    EXPECT_EQ(dm.num_points(), tess_->vertexCount()) << "Draco kept every vertex";
    for (const auto& [name, id] : extension["attributes"].items()) {
        const draco::PointAttribute* attribute = dm.GetAttributeByUniqueId(id.get<uint32_t>());
        ASSERT_NE(attribute, nullptr) << name;
        const int components = attribute->num_components();
        EXPECT_EQ(components, name == "TANGENT" ? 4 : name == "TEXCOORD_0" ? 2 : 3) << name;
        for (draco::PointIndex p(0); p < dm.num_points(); ++p) {
            float value[4];
            ASSERT_TRUE(attribute->ConvertValue<float>(attribute->mapped_index(p), components, value));
            ASSERT_TRUE(finite({value, size_t(components)})) << name << " point " << p.value();
            if (name == "TANGENT") {
                ASSERT_NEAR(std::abs(value[3]), 1.0f, 1e-3f);
            }
            if (name == "NORMAL") {
                ASSERT_NEAR(glm::length(glm::vec3(value[0], value[1], value[2])), 1.0f, 1e-2f);
            }
        }
    }
}

// No image, no material: the surface is drawn as a reader draws a mesh without one, as it drew
// a reference that had none (not in a grey of subdfit's own).
TEST_F(ExportGlb, GlbWithoutNormalMapHasNoTexture) {
    const io::WrittenFile file = writeFittedGlb(*dir_ / "untextured.glb", *tess_, FittedTextures{}, false);
    const json doc = readGlb(file.path).document;
    EXPECT_FALSE(doc.contains("images"));
    EXPECT_FALSE(doc.contains("textures"));
    EXPECT_FALSE(doc.contains("materials"));
    EXPECT_EQ(size_t(mesh::readGltf(file.path).vertexCount()), tess_->vertexCount());
}

// A cage ships as positions and indices only; with Draco (which reorders vertices) every
// vertex decodes within the 14-bit position quantisation of one of the cage's.
TEST_F(ExportGlb, PlainMeshGlbHasOnlyPositionsAndRoundTrips) {
    const mesh::PolygonMesh cage = mesh::triangulated(mesh::makeQuadSphere(3));
    const std::vector<std::uint32_t> indices(cage.faceIndices.begin(), cage.faceIndices.end());
    for (bool draco : {false, true}) {
        SCOPED_TRACE(draco ? "draco" : "plain");
        const io::WrittenFile file = writeMeshGlb(*dir_ / (draco ? "cage_draco.glb" : "cage.glb"), cage.positions, {},
                                                  indices, draco, {{"subdivision", "catmull-clark"}});
        const json doc = readGlb(file.path).document;
        EXPECT_EQ(doc["meshes"][0]["extras"]["subdivision"], "catmull-clark");
        EXPECT_EQ(doc["meshes"][0]["primitives"][0]["attributes"].size(), 1u);
        EXPECT_FALSE(doc.contains("materials"));
        const mesh::PolygonMesh read = mesh::readGltf(file.path);
        ASSERT_EQ(read.faceCount(), cage.faceCount());
        ASSERT_EQ(read.vertexCount(), cage.vertexCount());
        float worst = 0.0f;
        for (const glm::vec3& p : read.positions) {
            float nearest = 1e9f;
            for (const glm::vec3& q : cage.positions) nearest = std::min(nearest, glm::length(p - q));
            worst = std::max(worst, nearest);
        }
        EXPECT_LT(worst, draco ? 2e-4f : 1e-7f);
        if (!draco) {
            EXPECT_EQ(read.faceIndices, cage.faceIndices);
        }
    }
}

TEST_F(ExportGlb, UnwritableDestinationThrowsAndLeavesNoTemporary) {
    const fs::path dir = test::scratchDir("export_glb_unwritable");
    std::ofstream(dir / "file") << "not a folder";
    fs::create_directory(dir / "taken.glb");
    for (const fs::path& destination : {dir / "file" / "out.glb", dir / "missing" / "out.glb", dir / "taken.glb"})
        for (bool draco : {false, true}) {
            SCOPED_TRACE(destination.string());
            try {
                writeFittedGlb(destination, *tess_, *png_, draco);
                ADD_FAILURE() << "expected subdfit::Error";
            } catch (const Error& e) {
                EXPECT_EQ(std::string(e.what()).rfind(destination.string() + ": ", 0), 0u) << e.what();
            }
        }
    std::vector<std::string> left;
    for (const auto& entry : fs::directory_iterator(dir)) left.push_back(entry.path().filename().string());
    std::sort(left.begin(), left.end());
    EXPECT_EQ(left, (std::vector<std::string>{"file", "taken.glb"}));
    EXPECT_TRUE(fs::is_empty(dir / "taken.glb"));
}

TEST(ExportTessellation, TriangleCageIsWoundOutwards) {
    // An icosahedron: every ptex face is a sub-quad of a triangle.
    const mesh::PolygonMesh cage = mesh::makeLumpySphere(0, 0.0f, 1);
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 2);
    maps.displacement.assign(size_t(maps.layout.nodeCount), 0.05f);
    const GltfMesh tess = fittedMesh(cage, maps, 4);
    EXPECT_EQ(tess.vertexCount(), 60u * 25);
    expectWellFormed(tess);
    expectOutward(tess);
}

TEST(ExportTessellation, CollapsedDerivativesStayFinite) {
    // Collapse a vertex's whole one-ring onto it: dP/du, dP/dv vanish along the collapsed
    // edges, one of them or both. (The surface genuinely folds near the pinch, so normals
    // pointing inwards there are right; only finiteness and unit length are checked.)
    mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    const int centre = cage.faceIndices[0];
    std::vector<int> ring;
    for (int f = 0; f < cage.faceCount(); ++f) {
        const std::span<const int> quad(&cage.faceIndices[size_t(f) * 4], 4);
        if (std::find(quad.begin(), quad.end(), centre) != quad.end())
            ring.insert(ring.end(), quad.begin(), quad.end());
    }
    for (int v : ring) cage.positions[size_t(v)] = cage.positions[size_t(centre)];
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 3);
    for (int n = 0; n < maps.layout.nodeCount; ++n) maps.displacement.push_back(0.02f * std::sin(float(n)));
    const GltfMesh tess = fittedMesh(cage, maps, 6);
    expectWellFormed(tess);
}

TEST(ExportTessellation, CageCollapsedToAPointStaysFinite) {
    mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    for (glm::vec3& p : cage.positions) p = glm::vec3(0.5f);
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 2);
    maps.displacement.assign(size_t(maps.layout.nodeCount), 0.1f);
    const GltfMesh tess = fittedMesh(cage, maps, 2);
    expectWellFormed(tess);
}

TEST(ExportTessellation, HolesAreSkipped) {
    mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    cage.tags.holes = {0, 5};
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 2);
    const GltfMesh tess = fittedMesh(cage, maps, 2);
    EXPECT_EQ(tess.vertexCount(), (54u - 2u) * 9u);
    expectWellFormed(tess);
}

TEST(ExportTessellation, SegmentCountIsValidated) {
    const Asset asset;
    EXPECT_THROW(fittedMesh(asset.cage, asset.maps, 0), Error);
    EXPECT_THROW(fittedMesh(asset.cage, asset.maps, 1025), Error);
}

}  // namespace
}  // namespace subdfit::exporter
