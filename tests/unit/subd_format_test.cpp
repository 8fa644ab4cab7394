// The shipped .subd file: what is decoded is what was fitted, within the quantisation steps, and
// anything that is not a whole version-1 file is refused in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

#include "error_message.h"
#include <glm/geometric.hpp>

#include "export/node_coding.h"
#include "export/subd_decode.h"
#include "export/subd_format.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

// Smooth heights and normal-map offsets with some fine detail, on the cage's texel layout.
surface::SurfaceMaps someMaps(const mesh::PolygonMesh& cage, int resolution, std::uint32_t seed) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, resolution);
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 0.002f);
    const auto limit = surface::tessellate(cage, {}, resolution);
    maps.displacement.assign(size_t(maps.layout.nodeCount), 0.0f);
    maps.normal.assign(size_t(maps.layout.nodeCount) * 2, 0.0f);
    // Each node's value from where it lies on the limit surface: continuous across tiles.
    // (Holes have no surface: their nodes keep 0.)
    for (size_t k = 0; k < limit.vertexCount(); ++k) {
        const auto& at = limit.ptex[k];
        const int node = maps.layout.node(at.face, int(std::lround(at.u * float(resolution))),
                                          int(std::lround(at.v * float(resolution))));
        const glm::vec3 p = limit.positions[k];
        maps.displacement[size_t(node)] = 0.05f * std::sin(4.0f * p.x) * std::cos(3.0f * p.y) + noise(rng);
        maps.normal[2 * size_t(node)] = 0.3f * std::sin(5.0f * p.z);
        maps.normal[2 * size_t(node) + 1] = 0.2f * std::cos(2.0f * p.x);
    }
    return maps;
}

float largestDistance(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    float worst = 0.0f;
    for (size_t k = 0; k < a.size(); ++k) worst = std::max(worst, glm::length(a[k] - b[k]));
    return worst;
}

class SubdRoundTrip : public ::testing::TestWithParam<const char*> {};

TEST_P(SubdRoundTrip, DecodesTheFittedSurfaceWithinTheQuantisationSteps) {
    const auto cage = mesh::loadMesh(test::assetPath(std::string("osd-shapes/") + GetParam()));
    const auto maps = someMaps(cage, 4, 3);
    const SubdPrecision precision;
    const SubdAsset asset = shippableAsset(cage, maps, precision.positionBits);
    const auto bytes = encodeSubd(asset, precision);
    const SubdAsset decoded = decodeSubd(bytes, "round-trip");

    // The cage: same topology and tags, positions within half a quantisation step.
    EXPECT_EQ(decoded.cage.faceSizes, cage.faceSizes);
    EXPECT_EQ(decoded.cage.faceIndices, cage.faceIndices);
    EXPECT_EQ(decoded.cage.tags.creases, cage.tags.creases);
    EXPECT_EQ(decoded.cage.tags.corners, cage.tags.corners);
    EXPECT_EQ(decoded.cage.tags.holes, cage.tags.holes);
    EXPECT_EQ(decoded.cage.tags.boundary, cage.tags.boundary);
    float extent = 0.0f;
    for (const auto& p : cage.positions)
        for (const auto& q : cage.positions) extent = std::max({extent, std::abs(p.x - q.x), std::abs(p.y - q.y), std::abs(p.z - q.z)});
    const float positionStep = extent / 65535.0f;
    EXPECT_LE(largestDistance(decoded.cage.positions, cage.positions), positionStep * 0.87f + 1e-7f);

    // The maps: every node within half its channel's step.
    ASSERT_EQ(decoded.maps.layout.nodeCount, asset.maps.layout.nodeCount);
    auto worstError = [](const std::vector<float>& a, const std::vector<float>& b) {
        float worst = 0.0f;
        for (size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k]));
        return worst;
    };
    const float heightStep = quantisationFor(asset.maps.displacement, 1, 0, precision.displacementBits).step;
    EXPECT_LE(worstError(decoded.maps.displacement, asset.maps.displacement), 0.5f * heightStep * 1.001f);
    const float normalStep = std::max(quantisationFor(asset.maps.normal, 2, 0, precision.normalBits).step,
                                      quantisationFor(asset.maps.normal, 2, 1, precision.normalBits).step);
    EXPECT_LE(worstError(decoded.maps.normal, asset.maps.normal), 0.5f * normalStep * 1.001f);

    // The surface: the displaced limit surface moves by no more than the steps allow (the
    // limit stencils' weights sum to one; Catmull-Clark's absolute sums stay below 2).
    const auto before = surface::tessellate(cage, maps, 4), after = surface::tessellate(decoded.cage, decoded.maps, 4);
    ASSERT_EQ(before.vertexCount(), after.vertexCount());
    float largestHeight = 0.0f;
    for (float h : maps.displacement) largestHeight = std::max(largestHeight, std::abs(h));
    const float bound = 0.5f * heightStep + 2.0f * positionStep * 1.8f + largestHeight * 0.01f;
    EXPECT_LE(largestDistance(before.positions, after.positions), bound);

    // And it is compact: the three channels together in less than one float per node, beside
    // the cage's quantised positions and about two bytes per face corner.
    EXPECT_LT(bytes.size(), size_t(asset.maps.layout.nodeCount) * 4 + size_t(cage.vertexCount()) * 6 +
                                cage.faceIndices.size() * 2 + 100);
}

INSTANTIATE_TEST_SUITE_P(Shapes, SubdRoundTrip,
                         ::testing::Values("catmark_cube_creases1.obj", "catmark_torus_creases0.obj",
                                           "catmark_hole_test1.obj", "catmark_smoothtris0.obj", "catmark_bishop.obj"),
                         [](const auto& info) {
                             std::string name = info.param;
                             return name.substr(0, name.find('.'));
                         });

TEST(SubdFormat, ACageWithoutMapsRoundTrips) {
    const auto cage = mesh::makeQuadSphere(4);
    const auto decoded = decodeSubd(encodeSubd({.cage = cage, .maps = {}}), "no maps");
    EXPECT_EQ(decoded.cage.faceIndices, cage.faceIndices);
    EXPECT_EQ(decoded.maps.layout.resolution, 0);
    EXPECT_FALSE(decoded.maps.hasDisplacement());
}

TEST(SubdFormat, AnythingButAWholeVersionOneFileIsRefusedInOneLine) {
    const auto cage = mesh::makeQuadSphere(3);
    const auto good = encodeSubd(shippableAsset(cage, someMaps(cage, 2, 1)));
    auto expectRefused = [](std::vector<unsigned char> bytes, const std::string& expected) {
        const std::string message = test::errorMessage([&] { decodeSubd(bytes, "bad.subd"); });
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
        EXPECT_EQ(message.rfind("bad.subd: ", 0), 0u) << message;
        EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in: " << message;
    };
    expectRefused({}, "not a .subd file");
    expectRefused({'S', 'U', 'B', 'D', 1}, "truncated");
    expectRefused({good.begin(), good.begin() + good.size() / 2}, "checksum");
    auto version = good;
    version[4] = 9;
    expectRefused(version, "version 9");
    auto flipped = good;
    flipped[good.size() / 2] ^= 0x40;
    expectRefused(flipped, "checksum");
    auto garbage = good;
    for (size_t k = 8; k < garbage.size(); ++k) garbage[k] = static_cast<unsigned char>(k * 131);
    expectRefused(garbage, "checksum");
}

TEST(SubdDecode, WritesTheDisplacedSurfaceAndNothingForABadFile) {
    const auto dir = test::scratchDir("subd_decode");
    const auto cage = mesh::makeQuadSphere(3);
    writeSubd(dir / "asset.subd", shippableAsset(cage, someMaps(cage, 4, 2)));
    const auto written = decodeToGlb(dir / "asset.subd", dir / "decoded.glb");
    const auto mesh = mesh::loadMesh(written.path);
    EXPECT_EQ(mesh.faceCount(), cage.faceCount() * 4 * 4 * 2);  // 4 segments (the maps' T), 2 triangles each

    {
        std::ofstream truncated(dir / "truncated.subd", std::ios::binary);
        truncated << "SUBD\x01";
    }
    EXPECT_THROW(decodeToGlb(dir / "truncated.subd", dir / "never.glb"), Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "never.glb"));
    EXPECT_THROW(decodeToGlb(dir / "missing.subd", dir / "never.glb"), Error);
}

}  // namespace
}  // namespace subdfit::exporter
