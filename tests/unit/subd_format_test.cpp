// The shipped .subd file: what is decoded is what was fitted, within the quantisation steps, and
// anything that is not a whole .subd file of a version this subdfit reads is refused in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numeric>
#include <random>

#include "error_message.h"
#include <glm/geometric.hpp>

#include "codec/cage_coding.h"
#include "codec/node_coding.h"
#include "export/engine/subd_decode.h"
#include "codec/subd_format.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::codec {
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

// The cage renumbered as it decodes, with its own unquantised positions: what the decoded cage
// must match.
mesh::PolygonMesh renumbered(const mesh::PolygonMesh& cage, const CageCorrespondence& to,
                             const mesh::PolygonMesh& decoded) {
    mesh::PolygonMesh out = decoded;
    for (size_t v = 0; v < cage.positions.size(); ++v) out.positions[size_t(to.vertex[v])] = cage.positions[v];
    return out;
}

// The largest distance from a point of `a` to the nearest of `b` (`window`: how far apart in x
// two points may be and still be compared).
float farthestFrom(std::vector<glm::vec3> a, std::vector<glm::vec3> b, float window) {
    auto byX = [](const glm::vec3& p, const glm::vec3& q) { return p.x < q.x; };
    std::sort(b.begin(), b.end(), byX);
    float worst = 0.0f;
    for (const auto& p : a) {
        float nearest = window;
        for (auto it = std::lower_bound(b.begin(), b.end(), p - glm::vec3(window, 0, 0), byX);
             it != b.end() && it->x <= p.x + window; ++it)
            nearest = std::min(nearest, glm::length(*it - p));
        worst = std::max(worst, nearest);
    }
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
    const CodedCage coded = encodeCage(cage, precision.positionBits);
    const CageCorrespondence& to = coded.correspondence;

    // The cage: the same faces (renumbered, maybe starting at another corner), the same tags.
    ASSERT_EQ(decoded.cage.faceCount(), cage.faceCount());
    ASSERT_EQ(decoded.cage.vertexCount(), cage.vertexCount());
    EXPECT_EQ(decoded.cage.faceIndices, coded.decoded.faceIndices);
    std::vector<int> first(1, 0);
    for (int n : decoded.cage.faceSizes) first.push_back(first.back() + n);
    for (int f = 0, at = 0; f < cage.faceCount(); at += cage.faceSizes[size_t(f)], ++f) {
        const int n = cage.faceSizes[size_t(f)], g = to.face[size_t(f)];
        ASSERT_EQ(decoded.cage.faceSizes[size_t(g)], n);
        for (int k = 0; k < n; ++k)
            ASSERT_EQ(decoded.cage.faceIndices[size_t(first[size_t(g)] + k)],
                      to.vertex[size_t(cage.faceIndices[size_t(at + (k + to.rotation[size_t(f)]) % n)])]);
    }
    const auto& tags = decoded.cage.tags;
    ASSERT_EQ(tags.creases.size(), cage.tags.creases.size());
    for (size_t k = 0; k < tags.creases.size(); ++k) {
        EXPECT_EQ(tags.creases[k].v0, to.vertex[size_t(cage.tags.creases[k].v0)]);
        EXPECT_EQ(tags.creases[k].v1, to.vertex[size_t(cage.tags.creases[k].v1)]);
        EXPECT_EQ(tags.creases[k].sharpness, cage.tags.creases[k].sharpness);
    }
    ASSERT_EQ(tags.corners.size(), cage.tags.corners.size());
    for (size_t k = 0; k < tags.corners.size(); ++k)
        EXPECT_EQ(tags.corners[k].vertex, to.vertex[size_t(cage.tags.corners[k].vertex)]);
    ASSERT_EQ(tags.holes.size(), cage.tags.holes.size());
    for (size_t k = 0; k < tags.holes.size(); ++k) EXPECT_EQ(tags.holes[k], to.face[size_t(cage.tags.holes[k])]);
    EXPECT_EQ(tags.boundary, cage.tags.boundary);
    // Positions within half a quantisation step per axis.
    const auto reference = renumbered(cage, to, decoded.cage);
    float extent = 0.0f;
    for (const auto& p : cage.positions)
        for (const auto& q : cage.positions)
            extent = std::max({extent, std::abs(p.x - q.x), std::abs(p.y - q.y), std::abs(p.z - q.z)});
    const float positionStep = extent / float((1 << precision.positionBits) - 1);
    EXPECT_LE(largestDistance(decoded.cage.positions, reference.positions), positionStep * 0.87f + 1e-7f);

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
    // limit stencils' weights sum to one; Catmull-Clark's absolute sums stay below 2); and the
    // maps carried onto the renumbered cage give the surface they gave before, point for point
    // (a tile carried to the wrong face or turned the wrong way would move points by the heights).
    const auto before = surface::tessellate(reference, asset.maps, 4),
               after = surface::tessellate(decoded.cage, decoded.maps, 4);
    ASSERT_EQ(before.vertexCount(), after.vertexCount());
    float largestHeight = 0.0f;
    for (float h : maps.displacement) largestHeight = std::max(largestHeight, std::abs(h));
    const float bound = 0.5f * heightStep + 2.0f * positionStep * 1.8f + largestHeight * 0.01f;
    EXPECT_LE(farthestFrom(after.positions, before.positions, 2.0f * bound), bound);
    EXPECT_LE(farthestFrom(surface::tessellate(cage, maps, 4).positions, before.positions, bound), 1e-4f);

    // And it is compact: the three channels together in less than one float per node, beside
    // the cage's quantised positions and about two bytes per face corner.
    EXPECT_LT(bytes.size(), size_t(asset.maps.layout.nodeCount) * 4 + size_t(cage.vertexCount()) * 6 +
                                cage.faceIndices.size() * 2 + 100);
}

INSTANTIATE_TEST_SUITE_P(Shapes, SubdRoundTrip,
                         ::testing::Values("catmark_cube_creases1.obj", "catmark_torus_creases0.obj",
                                           "catmark_hole_test1.obj", "catmark_smoothtris0.obj", "catmark_bishop.obj",
                                           "catmark_nonman_quadpole64.obj", "catmark_chaikin0.obj"),
                         [](const auto& info) {
                             std::string name = info.param;
                             return name.substr(0, name.find('.'));
                         });

TEST(SubdFormat, ACageWithoutMapsRoundTrips) {
    const auto cage = mesh::makeQuadSphere(4);
    const auto decoded = decodeSubd(encodeSubd({.cage = cage, .maps = {}}), "no maps");
    EXPECT_EQ(decoded.cage.faceIndices, encodeCage(cage, SubdPrecision{}.positionBits).decoded.faceIndices);
    EXPECT_EQ(decoded.maps.layout.resolution, 0);
    EXPECT_FALSE(decoded.maps.hasDisplacement());
}

// What a fit of the coded asset draws (fit/coded_refinement.h) is what a file's decoder reads:
// the same quantisation and leans, node for node, at the few bits budgets ask for and at more.
TEST(SubdFormat, CodedValuesAreWhatTheFileDecodesTo) {
    const auto cage = mesh::makeQuadSphere(4);
    for (const int bits : {4, 8}) {
        const SubdAsset asset = shippableAsset(cage, someMaps(cage, 4, 9));
        const SubdAsset decoded = decodeSubd(encodeSubd(asset, SubdPrecision::forMapBits(bits)), "heights");
        const std::vector<float> coded = codedValues(asset.maps.layout, asset.maps.displacement, 1, bits);
        ASSERT_EQ(coded.size(), decoded.maps.displacement.size());
        int differing = 0;
        for (size_t n = 0; n < coded.size(); ++n) differing += coded[n] != decoded.maps.displacement[n];
        EXPECT_EQ(differing, 0) << bits << " bits";
        EXPECT_NE(coded, asset.maps.displacement) << "coding at " << bits << " bits rounds the heights";
    }
}

// The appearance maps ship as JPEGs of their atlas: what decodes is within a few 8-bit steps of
// what was fitted where the colours vary smoothly, on the decoded cage's own lattice.
// Tiles of `resolution` cells on `cage` whose base colour and roughness follow each node's limit
// position (metallic 0.3).
surface::SurfaceMaps tilesColouredByPosition(const mesh::PolygonMesh& cage, int resolution) {
    surface::SurfaceMaps maps;
    maps.appearanceLayout = surface::buildTexelLayout(cage, resolution);
    const auto limit = surface::tessellate(cage, {}, resolution);
    const size_t nodes = size_t(maps.appearanceLayout.nodeCount);
    maps.baseColor.assign(3 * nodes, 0.0f);
    maps.metallicRoughness.assign(2 * nodes, 0.0f);
    for (size_t k = 0; k < limit.vertexCount(); ++k) {
        const auto& at = limit.ptex[k];
        const size_t n = size_t(maps.appearanceLayout.node(at.face, int(std::lround(at.u * float(resolution))),
                                                           int(std::lround(at.v * float(resolution)))));
        const glm::vec3 p = limit.positions[k];
        maps.baseColor[3 * n] = 0.5f + 0.3f * p.x;
        maps.baseColor[3 * n + 1] = 0.5f + 0.3f * p.y;
        maps.baseColor[3 * n + 2] = 0.5f - 0.3f * p.z;
        maps.metallicRoughness[2 * n] = 0.6f + 0.2f * p.y;
        maps.metallicRoughness[2 * n + 1] = 0.3f;
    }
    return maps;
}

TEST(SubdFormat, AppearanceMapsRoundTripWithinJpegError) {
    const auto cage = mesh::makeQuadSphere(3);
    const surface::SurfaceMaps maps = tilesColouredByPosition(cage, 6);
    const SubdAsset shipped = shippableAsset(cage, maps);
    const SubdAsset decoded = decodeSubd(encodeSubd(shipped), "colours");
    ASSERT_TRUE(decoded.maps.hasBaseColor());
    ASSERT_TRUE(decoded.maps.hasMetallicRoughness());
    ASSERT_EQ(decoded.maps.baseColor.size(), shipped.maps.baseColor.size());
    double worst = 0.0, sum = 0.0;
    for (size_t k = 0; k < shipped.maps.baseColor.size(); ++k) {
        const double e = std::abs(double(decoded.maps.baseColor[k]) - double(shipped.maps.baseColor[k]));
        worst = std::max(worst, e);
        sum += e;
    }
    std::printf("base colour after JPEG: mean error %.4f, worst %.4f\n", sum / double(shipped.maps.baseColor.size()),
                worst);
    // JPEG at quality 90 with full chroma: a few 8-bit steps on average, more at tile borders,
    // where the atlas puts unrelated faces side by side.
    EXPECT_LT(sum / double(shipped.maps.baseColor.size()), 4.0 / 255.0);
    EXPECT_LT(worst, 0.1);
    for (size_t k = 0; k < shipped.maps.metallicRoughness.size(); ++k)
        EXPECT_NEAR(decoded.maps.metallicRoughness[k], shipped.maps.metallicRoughness[k], 0.06) << k;
}

// The reference's emission and occlusion carried on tiles ship too (EMIS; MTRG's red), their
// nodes following the cage's coding as the base colour's do: an emission equal to the base colour
// and an occlusion equal to its red stay so.
TEST(SubdFormat, EmissionAndOcclusionOnTilesRoundTrip) {
    const auto cage = mesh::makeQuadSphere(3);
    surface::SurfaceMaps maps = tilesColouredByPosition(cage, 4);
    const size_t nodes = size_t(maps.appearanceLayout.nodeCount);
    maps.emissive = maps.baseColor;
    for (size_t n = 0; n < nodes; ++n) maps.occlusion.push_back(maps.baseColor[3 * n]);
    const SubdAsset shipped = shippableAsset(cage, maps);
    ASSERT_EQ(shipped.maps.emissive, shipped.maps.baseColor);
    const SubdAsset decoded = decodeSubd(encodeSubd(shipped), "glow");
    ASSERT_EQ(decoded.maps.emissive.size(), 3 * nodes);
    ASSERT_EQ(decoded.maps.occlusion.size(), nodes);
    double emission = 0.0, occlusion = 0.0;
    for (size_t k = 0; k < 3 * nodes; ++k)
        emission += std::abs(double(decoded.maps.emissive[k]) - double(shipped.maps.baseColor[k]));
    for (size_t n = 0; n < nodes; ++n)
        occlusion += std::abs(double(decoded.maps.occlusion[n]) - double(shipped.maps.baseColor[3 * n]));
    EXPECT_LT(emission / double(3 * nodes), 4.0 / 255.0);  // JPEG at quality 90, as the base colour
    EXPECT_LT(occlusion / double(nodes), 4.0 / 255.0);
}

TEST(SubdFormat, AnythingButAWholeVersionThreeFileIsRefusedInOneLine) {
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
    version[4] = 200;
    expectRefused(version, "version 200");
    auto flipped = good;
    flipped[good.size() / 2] ^= 0x40;
    expectRefused(flipped, "checksum");
    auto garbage = good;
    for (size_t k = 8; k < garbage.size(); ++k) garbage[k] = static_cast<unsigned char>(k * 131);
    expectRefused(garbage, "checksum");
}

// A file written before the heights were coded level by level (box.subd: version 7, its
// residuals tile by tile as varints) decodes to the heights it held: the figures are what the
// build that wrote it decodes (its `decode` .glb and this one's are the same bytes).
TEST(SubdFormat, AFileCodedTileByTileDecodesToTheHeightsItHeld) {
    const auto asset = readSubd(std::filesystem::path(SUBDFIT_SOURCE_DIR) / "tests/data/damaged-subd/box.subd");
    const std::vector<float>& heights = asset.maps.displacement;
    ASSERT_EQ(asset.maps.layout.resolution, 2);
    ASSERT_EQ(heights.size(), 26u);
    EXPECT_NEAR(std::accumulate(heights.begin(), heights.end(), 0.0), -0.127144121, 1e-8);
    EXPECT_FLOAT_EQ(heights.front(), -0.00503052492f);
    EXPECT_FLOAT_EQ(heights.back(), -0.00454217475f);
    EXPECT_FLOAT_EQ(*std::min_element(heights.begin(), heights.end()), -0.00519900583f);
    EXPECT_FLOAT_EQ(*std::max_element(heights.begin(), heights.end()), -0.0044402387f);
}

TEST(SubdDecode, WritesTheDisplacedSurfaceAndNothingForABadFile) {
    const auto dir = test::scratchDir("subd_decode");
    const auto cage = mesh::makeQuadSphere(3);
    writeSubd(dir / "asset.subd", shippableAsset(cage, someMaps(cage, 4, 2)));
    const auto written = exporter::decodeToGlb(dir / "asset.subd", dir / "decoded.glb");
    const auto mesh = mesh::loadMesh(written.path);
    EXPECT_EQ(mesh.faceCount(), cage.faceCount() * 4 * 4 * 2);  // 4 segments (the maps' T), 2 triangles each

    {
        std::ofstream truncated(dir / "truncated.subd", std::ios::binary);
        truncated << "SUBD\x01";
    }
    EXPECT_THROW(exporter::decodeToGlb(dir / "truncated.subd", dir / "never.glb"), Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "never.glb"));
    EXPECT_THROW(exporter::decodeToGlb(dir / "missing.subd", dir / "never.glb"), Error);
}

}  // namespace
}  // namespace subdfit::codec

namespace subdfit::codec {
namespace {

// A decimator's cage comes in no useful vertex order: the plain coding's index deltas are then
// as large as the cage (~1.5 bytes each after zstd) and its positions barely compress (the
// previous format: 13.5 bytes per vertex on a 1 000-face bunny cage). Draco's edgebreaker
// and parallelogram prediction do not care about the order.
TEST(SubdFormat, AShuffledCageShipsInFewBytesPerVertex) {
    auto cage = mesh::loadMesh(test::assetPath("osd-shapes/catmark_bishop.obj"));
    std::vector<int> order(size_t(cage.vertexCount()));
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(7));
    mesh::PolygonMesh shuffled = cage;
    for (size_t v = 0; v < order.size(); ++v) shuffled.positions[size_t(order[v])] = cage.positions[v];
    for (int& index : shuffled.faceIndices) index = order[size_t(index)];
    for (auto& c : shuffled.tags.creases) c = {order[size_t(c.v0)], order[size_t(c.v1)], c.sharpness};
    for (auto& c : shuffled.tags.corners) c.vertex = order[size_t(c.vertex)];
    const auto bytes = encodeSubd({.cage = shuffled, .maps = {}});
    EXPECT_LT(bytes.size(), size_t(cage.vertexCount()) * 6);  // what the plain positions alone take (4.4 measured)
    EXPECT_EQ(decodeSubd(bytes, "shuffled").cage.faceCount(), cage.faceCount());
}

}  // namespace
}  // namespace subdfit::codec
