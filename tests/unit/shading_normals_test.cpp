// A reference is shaded with its author's normals (glTF NORMAL, carried through node transforms;
// OBJ vn) or, where it has none, as its viewers shade it: a glTF primitive flat (the spec's
// rule), an OBJ smooth, ignoring texture seams; never NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "mesh/mesh_loader.h"
#include "error_message.h"
#include "test_paths.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;

void writeBytes(const fs::path& path, const std::vector<float>& values) {
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()), std::streamsize(values.size() * sizeof(float)));
}

// One triangle (0,0,0), (1,0,−1), (0,1,0) whose geometric normal is (1,0,1)/√2, with the given
// per-vertex NORMALs (none when empty), under a node with the given column-major matrix.
fs::path writeTriangle(const std::string& name, const std::vector<float>& normals, const std::string& matrix) {
    const fs::path dir = test::scratchDir("shading_normals_" + name);
    std::vector<float> data{0, 0, 0, 1, 0, -1, 0, 1, 0};
    data.insert(data.end(), normals.begin(), normals.end());
    writeBytes(dir / "t.bin", data);
    const std::string normalAccessor =
        normals.empty() ? "" : R"(,{"bufferView":0,"byteOffset":36,"componentType":5126,"count":3,"type":"VEC3"})";
    const std::string normalAttribute = normals.empty() ? "" : R"(,"NORMAL":1)";
    std::ofstream(dir / "t.gltf") << R"({"asset":{"version":"2.0"},
  "buffers":[{"uri":"t.bin","byteLength":)" +
                                         std::to_string(data.size() * 4) + R"(}],
  "bufferViews":[{"buffer":0,"byteLength":)" +
                                         std::to_string(data.size() * 4) + R"(}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,-1],"max":[1,1,0]})" +
                                         normalAccessor + R"(],
  "materials":[{}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0)" +
                                         normalAttribute + R"(},"material":0}]}],
  "nodes":[{"mesh":0,"matrix":)" + matrix +
                                         R"(}],"scenes":[{"nodes":[0]}],"scene":0})";
    return dir / "t.gltf";
}

const std::string kIdentity = "[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]";
// Mirrored in x and stretched unevenly: a normal that only rotated would leave the surface.
const std::string kMirrorStretch = "[-1,0,0,0, 0,2,0,0, 0,0,3,0, 0,0,0,1]";

glm::vec3 geometricNormal(const PolygonMesh& m) {
    const glm::vec3 a = m.positions[size_t(m.faceIndices[0])], b = m.positions[size_t(m.faceIndices[1])],
                    c = m.positions[size_t(m.faceIndices[2])];
    return glm::normalize(glm::cross(b - a, c - a));
}

TEST(ShadingNormals, AuthoredNormalsFollowTheNodeTransformAndStayOutward) {
    const float s = 1.0f / std::sqrt(2.0f);
    const std::vector<float> authored{s, 0, s, s, 0, s, s, 0, s};
    for (const std::string& matrix : {kIdentity, kMirrorStretch}) {
        const PolygonMesh m = loadReference(writeTriangle("transform", authored, matrix));
        ASSERT_EQ(m.normals.size(), 3u) << matrix;
        const glm::vec3 expected = geometricNormal(m);  // of the winding as read (the reader undoes the mirror)
        for (const glm::vec3& n : m.normals) {
            EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f) << matrix;
            EXPECT_GT(glm::dot(n, expected), 0.99999f) << matrix;
        }
        const auto shaded = shadingNormals(triangulated(m));
        EXPECT_EQ(shaded, m.normals) << "triangulated() and shadingNormals() keep the author's normals";
    }
}

TEST(ShadingNormals, AZeroNormalBecomesTheSurfacesOwn) {
    const float s = 1.0f / std::sqrt(2.0f);
    const PolygonMesh m = loadReference(writeTriangle("zero", {0, 0, 0, s, 0, s, 0, 0, 2}, kIdentity));
    ASSERT_EQ(m.normals.size(), 3u);
    EXPECT_GT(glm::dot(m.normals[0], geometricNormal(m)), 0.99999f);
    EXPECT_NEAR(m.normals[2].z, 1.0f, 1e-6f) << "a long normal is normalised, not replaced";
}

TEST(ShadingNormals, WithoutNormalAGltfTriangleIsShadedFlatAndGeometryReadsSkipThem) {
    const PolygonMesh m = loadReference(writeTriangle("none", {}, kIdentity));
    ASSERT_EQ(m.normals.size(), 3u);
    for (const glm::vec3& n : m.normals) EXPECT_GT(glm::dot(n, geometricNormal(m)), 0.99999f);
    EXPECT_EQ(shadingNormals(m), m.normals);
    const float s = 1.0f / std::sqrt(2.0f);
    EXPECT_TRUE(loadMesh(writeTriangle("geometry", {s, 0, s, s, 0, s, s, 0, s}, kIdentity)).normals.empty());
}

// Two triangles folded 90° along the edge they share, (0,0,0)-(1,0,0), with no NORMAL: a glTF
// viewer draws each flat, so the fold stays sharp; smooth normals would round it.
TEST(ShadingNormals, WithoutNormalAGltfPrimitiveSplitsItsVerticesAtEveryEdge) {
    const fs::path dir = test::scratchDir("shading_normals_fold");
    writeBytes(dir / "f.bin", {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1});
    const std::vector<std::uint16_t> indices{0, 1, 2, 1, 0, 3};
    std::ofstream(dir / "i.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(indices.data()), std::streamsize(indices.size() * 2));
    std::ofstream(dir / "f.gltf") << R"({"asset":{"version":"2.0"},
  "buffers":[{"uri":"f.bin","byteLength":48},{"uri":"i.bin","byteLength":12}],
  "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":1,"byteLength":12}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,1]},
               {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
  "nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
    const PolygonMesh m = loadReference(dir / "f.gltf");
    ASSERT_EQ(m.faceCount(), 2);
    ASSERT_EQ(m.vertexCount(), 6) << "each triangle its own three vertices";
    ASSERT_EQ(m.normals.size(), 6u);
    for (int f = 0; f < 2; ++f) {
        const glm::vec3 a = m.positions[size_t(m.faceIndices[size_t(3 * f)])],
                        b = m.positions[size_t(m.faceIndices[size_t(3 * f + 1)])],
                        c = m.positions[size_t(m.faceIndices[size_t(3 * f + 2)])];
        const glm::vec3 face = glm::normalize(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k)
            EXPECT_GT(glm::dot(m.normals[size_t(m.faceIndices[size_t(3 * f + k)])], face), 0.99999f) << f;
    }
    EXPECT_LT(std::abs(glm::dot(m.normals[size_t(m.faceIndices[0])], m.normals[size_t(m.faceIndices[3])])), 1e-5f)
        << "the two sides keep their own normals, 90° apart";
    EXPECT_EQ(loadMesh(dir / "f.gltf").vertexCount(), 4) << "a geometry read keeps the shared vertices";
}

TEST(ShadingNormals, ANonFiniteNormalIsRefusedNamingTheFile) {
    const fs::path path = writeTriangle("nan", {0, 0, 1, std::nanf(""), 0, 1, 0, 0, 1}, kIdentity);
    const std::string message = test::errorMessage([&] { loadReference(path); });
    EXPECT_NE(message.find("t.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("non-finite normal"), std::string::npos) << message;
}

TEST(ShadingNormals, TheDuckKeepsItsAuthoredNormals) {
    const PolygonMesh duck = triangulated(loadReference(test::assetPath("gltf/Duck/Duck.glb")));
    ASSERT_EQ(duck.normals.size(), duck.positions.size());
    // Authored, not recomputed: they differ from the split vertices' own somewhere, yet face
    // the same side everywhere but at a few folds.
    const auto computed = vertexNormals(duck);
    size_t differ = 0, sameSide = 0;
    for (size_t v = 0; v < computed.size(); ++v) {
        EXPECT_NEAR(glm::length(duck.normals[v]), 1.0f, 1e-4f);
        differ += glm::dot(duck.normals[v], computed[v]) < std::cos(glm::radians(5.0f));
        sameSide += glm::dot(duck.normals[v], computed[v]) > 0.0f;
    }
    EXPECT_GT(differ, computed.size() / 100);
    EXPECT_GT(sameSide, computed.size() * 99 / 100);
}

TEST(ShadingNormals, AnObjTextureSeamDoesNotCreaseTheShading) {
    const fs::path dir = test::scratchDir("shading_normals_obj");
    std::ofstream(dir / "m.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                                    "f 1/1 2/2 3/3\nf 1/5 3/3 4/4\n";
    const PolygonMesh m = loadReference(dir / "m.obj");
    ASSERT_EQ(m.vertexCount(), 5);  // position 1 split by its two texture coordinates
    ASSERT_EQ(m.normals.size(), 5u);
    int first = -1;
    for (int v = 0; v < m.vertexCount(); ++v) {
        if (m.positions[size_t(v)] != glm::vec3(0.0f)) continue;
        if (first < 0) first = v;
        else
            EXPECT_GT(glm::dot(m.normals[size_t(first)], m.normals[size_t(v)]), 0.99999f)
                << "the two copies shade alike";
    }
    // And the split copies are not each their own face's flat normal: both faces were averaged.
    const auto split = vertexNormals(m);
    EXPECT_LT(glm::dot(split[size_t(first)], m.normals[size_t(first)]), 0.9999f);
}

TEST(ShadingNormals, AnObjsVnAreItsShadingNormalsAndSplitItsVertices) {
    const fs::path dir = test::scratchDir("shading_normals_obj_vn");
    // Two triangles folded along their shared edge 1-3, each side with its own (hard) normal
    // there; the corner without a vn, and the one with a zero vn, take the smooth normal.
    std::ofstream(dir / "m.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nvn 0 0 3\nvn 0 -0.6 0.8\nvn 0 0 0\n"
                                    "f 1//1 2//1 3//1\nf 1//2 3//2 4//3\n";
    const PolygonMesh m = loadReference(dir / "m.obj");
    ASSERT_EQ(m.vertexCount(), 6);  // positions 1 and 3 each split by their two normals
    ASSERT_EQ(m.normals.size(), 6u);
    EXPECT_TRUE(m.uvs.empty());
    const auto smooth = vertexNormals(loadMesh(dir / "m.obj"));
    for (int f = 0; f < 2; ++f)
        for (int k = 0; k < 3; ++k) {
            const int v = m.faceIndices[size_t(3 * f + k)];
            const glm::vec3 expected = f == 0 ? glm::vec3(0, 0, 1) : k < 2 ? glm::vec3(0, -0.6f, 0.8f) : smooth[3];
            EXPECT_GT(glm::dot(m.normals[size_t(v)], expected), 0.99999f) << "face " << f << " corner " << k;
        }
    std::ofstream(dir / "bad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n";
    const std::string message = test::errorMessage([&] { loadReference(dir / "bad.obj"); });
    EXPECT_NE(message.find("bad.obj: line 5"), std::string::npos) << message;
    EXPECT_NE(message.find("normal index 2 is out of range"), std::string::npos) << message;
}

}  // namespace
}  // namespace subdfit::mesh
