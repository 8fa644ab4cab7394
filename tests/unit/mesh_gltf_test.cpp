// glTF, GLB and Draco reference meshes: the shared sample models, and our own small files in
// tests/data (node transforms, instancing, Draco .drc).
#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "mesh/draco_reader.h"
#include "mesh/gltf_reader.h"
#include "mesh/mesh_loader.h"
#include "test_paths.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;

fs::path dataPath(const std::string& name) { return fs::path(SUBDFIT_SOURCE_DIR) / "tests" / "data" / name; }

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
};

Bounds bounds(const PolygonMesh& mesh) {
    Bounds b;
    for (const glm::vec3& p : mesh.positions) b.lo = glm::min(b.lo, p), b.hi = glm::max(b.hi, p);
    return b;
}

bool allTriangles(const PolygonMesh& mesh) {
    for (int n : mesh.faceSizes)
        if (n != 3) return false;
    return true;
}

TEST(MeshGltf, SampleModelsHaveTheReadmeTriangleCounts) {
    SUBDFIT_REQUIRE_SHARED(dir, "gltf");
    const std::pair<const char*, int> models[] = {
        {"Box/glTF/Box.gltf", 12},
        {"Box/glTF-Binary/Box.glb", 12},
        {"Box/glTF-Embedded/Box.gltf", 12},
        {"Box/glTF-Draco-Binary/Box_Draco.glb", 12},
        {"BoxMetaDraco/glTF-Draco/BoxMetaDraco.gltf", 12},
        {"BoxTextured/glTF-Binary/BoxTextured.glb", 12},
        {"Duck/glTF/Duck.gltf", 4212},
        {"Duck/glTF-Binary/Duck.glb", 4212},
        {"NormalTangentTest/glTF-Binary/NormalTangentTest.glb", 7774},
    };
    for (const auto& [relative, triangles] : models) {
        SCOPED_TRACE(relative);
        const PolygonMesh mesh = loadMesh(dir / relative);
        EXPECT_EQ(mesh.faceCount(), triangles);
        EXPECT_TRUE(allTriangles(mesh));
        EXPECT_EQ(mesh.sourcePath, (dir / relative).string());
    }
}

TEST(MeshGltf, DracoBoxMatchesThePlainBox) {
    SUBDFIT_REQUIRE_SHARED(dir, "gltf");
    const PolygonMesh plain = readGltf(dir / "Box/glTF-Binary/Box.glb");
    const PolygonMesh draco = readGltf(dir / "Box/glTF-Draco-Binary/Box_Draco.glb");
    const Bounds a = bounds(plain), b = bounds(draco);
    // Draco quantises positions, so equal to its quantisation step, not to the bit.
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_NEAR(a.lo[axis], b.lo[axis], 1e-3f) << axis;
        EXPECT_NEAR(a.hi[axis], b.hi[axis], 1e-3f) << axis;
    }
    // The Box's root node turns Y-up into Z-up: the unit box must still be a unit box.
    EXPECT_NEAR(glm::length(a.hi - a.lo), std::sqrt(3.0f), 1e-5f);
}

TEST(MeshGltf, BoxMetaDracoAppliesItsNodeTranslation) {
    SUBDFIT_REQUIRE_SHARED(dir, "gltf");
    const Bounds b = bounds(readGltf(dir / "BoxMetaDraco/glTF-Draco/BoxMetaDraco.gltf"));
    EXPECT_NEAR(b.lo.z, 1.5f, 1e-3f);  // a unit box around the origin, moved by z = 2
    EXPECT_NEAR(b.hi.z, 2.5f, 1e-3f);
}

TEST(MeshGltf, InstancesEveryNodeWithItsTransformAndMirroredWinding) {
    const PolygonMesh mesh = readGltf(dataPath("triangle_instanced.gltf"));
    ASSERT_EQ(mesh.faceCount(), 2);
    ASSERT_EQ(mesh.vertexCount(), 6);
    EXPECT_EQ(mesh.positions[1], glm::vec3(11, 0, 0));  // translated by +10 x
    EXPECT_EQ(mesh.positions[4], glm::vec3(-1, 0, 0));  // mirrored in x
    // Both triangles face +Z: the mirrored copy had its winding flipped back.
    for (int f = 0; f < 2; ++f) {
        const glm::vec3 a = mesh.positions[size_t(mesh.faceIndices[3 * f])];
        const glm::vec3 b = mesh.positions[size_t(mesh.faceIndices[3 * f + 1])];
        const glm::vec3 c = mesh.positions[size_t(mesh.faceIndices[3 * f + 2])];
        EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << f;
    }
}

TEST(MeshGltf, ReadsOurGlb) {
    const PolygonMesh mesh = loadMesh(dataPath("triangle.glb"));
    EXPECT_EQ(mesh.faceCount(), 1);
    EXPECT_EQ(mesh.positions[2], glm::vec3(0, 1, 0));
}

TEST(MeshDraco, ReadsADrcMesh) {
    const PolygonMesh mesh = loadMesh(dataPath("tetrahedron.drc"));
    EXPECT_EQ(mesh.faceCount(), 4);
    EXPECT_TRUE(allTriangles(mesh));
    const Bounds b = bounds(mesh);
    EXPECT_EQ(b.lo, glm::vec3(0));
    EXPECT_EQ(b.hi, glm::vec3(1));
}

}  // namespace
}  // namespace subdfit::mesh

namespace subdfit::mesh {
namespace {

double area(const PolygonMesh& triangles) {
    double sum = 0.0;
    for (size_t t = 0; t + 2 < triangles.faceIndices.size(); t += 3) {
        auto p = [&](size_t k) { return triangles.positions[size_t(triangles.faceIndices[t + k])]; };
        sum += 0.5 * double(glm::length(glm::cross(p(1) - p(0), p(2) - p(0))));
    }
    return sum;
}

// What `gltfpack -cc` writes (EXT_meshopt_compression over KHR_mesh_quantization) reads as the
// same surface as its uncompressed output: the codecs are lossless.
TEST(MeshGltf, MeshoptCompressedGlbReadsAsItsUncompressedTwin) {
    const auto plain = loadMesh(dataPath("spot_gltfpack.glb"));
    const auto packed = loadMesh(dataPath("spot_gltfpack_cc.glb"));
    ASSERT_EQ(packed.faceCount(), plain.faceCount());
    EXPECT_GT(packed.faceCount(), 1000);
    const Bounds a = bounds(plain), b = bounds(packed);
    EXPECT_LT(glm::length(a.lo - b.lo) + glm::length(a.hi - b.hi), 1e-4f);
    EXPECT_NEAR(area(packed), area(plain), 1e-3 * area(plain));
}

}  // namespace
}  // namespace subdfit::mesh
