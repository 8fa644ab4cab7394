// The pieces of `simplify` that need no GL: welding, decimation, the limit-interpolated initial
// cage, ray casting, the bake, and the batch's sharding and naming.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <array>
#include <cmath>
#include <map>
#include <set>

#include "codec/subd_format.h"
#include "geometry/surface_distance.h"
#include "geometry/surface_queries.h"
#include "mesh/mesh_geometry.h"
#include "mesh/material_sampling.h"
#include "mesh/procedural.h"
#include "simplify/bake/bake.h"
#include "simplify/batch.h"
#include "simplify/cage/decimate.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/cage_bakes.h"
#include "simplify/prefix_growth.h"
#include "split_triangles.h"
#include "subdiv/limit_evaluator.h"
#include "surface/tessellation.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

// Every undirected edge's number of faces.
std::map<std::pair<int, int>, int> edgeUse(const mesh::PolygonMesh& m) {
    std::map<std::pair<int, int>, int> use;
    int first = 0;
    for (int size : m.faceSizes) {
        for (int k = 0; k < size; ++k) {
            const int a = m.faceIndices[size_t(first + k)], b = m.faceIndices[size_t(first + (k + 1) % size)];
            ++use[{std::min(a, b), std::max(a, b)}];
        }
        first += size;
    }
    return use;
}

TEST(SimplifyWeld, CoincidentVerticesBecomeOne) {
    const mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(4));
    const mesh::PolygonMesh welded = weldedTriangles(testing::splitTriangles(sphere));
    EXPECT_EQ(welded.vertexCount(), sphere.vertexCount());
    EXPECT_EQ(welded.faceCount(), sphere.faceCount());
    for (const auto& [edge, faces] : edgeUse(welded)) EXPECT_EQ(faces, 2);  // closed again
}

TEST(SimplifyDecimate, ClosedMeshStaysClosedWithinTheBudget) {
    const mesh::PolygonMesh dense = weldedTriangles(mesh::makeLumpySphere(4, 0.2f, 3));
    for (int target : {2000, 400, 60}) {
        SCOPED_TRACE(target);
        const mesh::PolygonMesh coarse = decimate(dense, target);
        EXPECT_LE(coarse.faceCount(), target);
        EXPECT_GE(coarse.faceCount(), target * 8 / 10);
        for (const auto& [edge, faces] : edgeUse(coarse)) ASSERT_EQ(faces, 2);
        for (int i = 0; i < coarse.faceCount(); ++i) {
            const int* f = &coarse.faceIndices[size_t(3 * i)];
            ASSERT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
        }
    }
    EXPECT_EQ(decimate(dense, dense.faceCount() + 10).faceCount(), dense.faceCount());
    EXPECT_THROW(decimate(dense, 0), Error);
}

// Clustering merges vertices cell by cell: within the count, on the input's own vertices (which
// the triangle baselines' normals are found by), components free to merge or vanish.
TEST(SimplifyCluster, StaysWithinTheCountOnTheInputsVertices) {
    const mesh::PolygonMesh sphere = weldedTriangles(mesh::makeQuadSphere(3));
    mesh::PolygonMesh many;  // 40 spheres on a grid
    for (int k = 0; k < 40; ++k) {
        const int first = many.vertexCount();
        for (const glm::vec3& p : sphere.positions)
            many.positions.push_back(p + glm::vec3(2.5f * float(k % 8), 2.5f * float(k / 8), 0));
        for (int i : sphere.faceIndices) many.faceIndices.push_back(first + i);
        many.faceSizes.insert(many.faceSizes.end(), sphere.faceSizes.begin(), sphere.faceSizes.end());
    }
    std::set<std::array<float, 3>> input;
    for (const glm::vec3& p : many.positions) input.insert({p.x, p.y, p.z});
    for (int target : {100, 600, 2000}) {
        SCOPED_TRACE(target);
        const mesh::PolygonMesh coarse = cluster(many, target);
        EXPECT_LE(coarse.faceCount(), target);
        EXPECT_GE(coarse.faceCount(), target / 4);
        for (const glm::vec3& p : coarse.positions) ASSERT_TRUE(input.count({p.x, p.y, p.z}));
        for (int i = 0; i < coarse.faceCount(); ++i) {
            const int* f = &coarse.faceIndices[size_t(3 * i)];
            ASSERT_TRUE(f[0] != f[1] && f[1] != f[2] && f[0] != f[2]);
        }
    }
    EXPECT_EQ(cluster(many, many.faceCount()).faceCount(), many.faceCount());
    EXPECT_THROW(cluster(many, 0), Error);
}

// Heights on `a`'s lattice sampled bilinearly at the nodes of `fine` (a finer lattice of its cage).
std::vector<float> onFinerLattice(const codec::SubdAsset& a, const surface::TexelLayout& fine) {
    const surface::TexelLayout& own = a.maps.layout;
    std::vector<float> out(size_t(fine.nodeCount), 0.0f);  // a bare cage's: none
    if (!a.maps.hasDisplacement()) return out;
    for (int face = 0; face < fine.ptexFaceCount; ++face)
        for (int j = 0; j <= fine.resolution; ++j)
            for (int i = 0; i <= fine.resolution; ++i) {
                const float u = float(i * own.resolution) / float(fine.resolution),
                            v = float(j * own.resolution) / float(fine.resolution);
                const int i0 = std::min(int(u), own.resolution - 1), j0 = std::min(int(v), own.resolution - 1);
                const float fu = u - float(i0), fv = v - float(j0);
                const auto h = [&](int di, int dj) {
                    return a.maps.displacement[size_t(own.node(face, i0 + di, j0 + dj))];
                };
                out[size_t(fine.node(face, i, j))] =
                    (1 - fv) * ((1 - fu) * h(0, 0) + fu * h(1, 0)) + fv * ((1 - fu) * h(0, 1) + fu * h(1, 1));
            }
    return out;
}

// --prefix's growth: finer lattices at the most bits that fit, weighed by the caller's measure
// (here how far the heights lie from the finest bake); the best ships where it beats the asset,
// and nothing grows where no finer file fits.
TEST(SimplifyPrefixGrowth, TheBestGrownFileWithinTheBudgetShips) {
    const mesh::PolygonMesh reference = mesh::triangulated(mesh::makeLumpySphere(5, 0.15f, 5, 40, 0.005f, 0.02f));
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    BakeOptions bake;
    bake.effects = {maps::MapKind::Displacement};
    bake.resolution = 2;
    const std::vector<unsigned char> small =
        codec::encodeSubd(codec::shippableAsset(cage, bakeMaps(cage, reference, bake)), {.displacementBits = 4});
    const GrowingAsset asset = growingAsset(small, "small", 4);
    ASSERT_EQ(whyNotGrown(asset.asset), "");
    const surface::TexelLayout finest = surface::buildTexelLayout(asset.asset.cage, kMostGrownResolution);
    const std::vector<float> truth = grownHeights(asset, reference, kMostGrownResolution);
    const auto loss = [&](const codec::SubdAsset& a) {
        const std::vector<float> h = onFinerLattice(a, finest);
        double sum = 0.0;
        for (size_t n = 0; n < h.size(); ++n) sum += std::abs(h[n] - truth[n]);
        return sum / double(h.size());
    };
    const std::uintmax_t budget = 6 * small.size();
    const Growth growth = growWithinBudget(asset, reference, budget, loss);
    ASSERT_FALSE(growth.file.empty()) << growth.why;
    EXPECT_LE(growth.file.size(), budget);
    EXPECT_EQ(growth.chosen.bytes, growth.file.size());
    EXPECT_LT(growth.chosen.loss, growth.assetLoss);
    int resolution = 2;
    for (const GrowthCandidate& c : growth.candidates) {
        EXPECT_EQ(c.resolution, 2 * resolution);
        resolution = c.resolution;
        EXPECT_LE(c.bytes, budget);
        EXPECT_GT(c.bits, 4);
        EXPECT_GE(c.loss, growth.chosen.loss);
    }
    // Its first bytes, as many as the asset's, decode to the asset; its whole to the lattice it
    // chose. A budget no finer file fits grows nothing.
    const codec::SubdAsset prefix =
        codec::decodeSubd(std::span(growth.file).first(small.size()), "grown", nullptr, {}, codec::SubdEnding::Prefix);
    EXPECT_EQ(prefix.cage.positions, asset.asset.cage.positions);
    EXPECT_EQ(prefix.maps.displacement, asset.asset.maps.displacement);
    EXPECT_EQ(codec::decodeSubd(growth.file, "grown").maps.layout.resolution, growth.chosen.resolution);
    const Growth none = growWithinBudget(asset, reference, small.size() + 1, loss);
    EXPECT_TRUE(none.file.empty());
    EXPECT_TRUE(none.candidates.empty());
    EXPECT_FALSE(none.why.empty());

    // A bare cage grows heights at any resolution; its first bytes, up to its own trailer, decode
    // to the cage alone.
    const std::vector<unsigned char> bareFile = codec::encodeSubd(codec::shippableAsset(cage, {}));
    const GrowingAsset bare = growingAsset(bareFile, "bare", 0);
    const Growth heights = growWithinBudget(bare, reference, 3 * small.size(), loss);
    ASSERT_FALSE(heights.file.empty()) << heights.why;
    EXPECT_LE(heights.file.size(), 3 * small.size());
    EXPECT_EQ(heights.candidates.front().resolution, kBareCageResolutions.front());
    EXPECT_GE(heights.chosen.bits, 4);
    const codec::SubdAsset cageAlone = codec::decodeSubd(std::span(heights.file).first(bareFile.size() - 8), "grown",
                                                         nullptr, {}, codec::SubdEnding::Prefix);
    EXPECT_EQ(cageAlone.cage.positions, bare.asset.cage.positions);
    EXPECT_TRUE(cageAlone.maps.displacement.empty());
    EXPECT_LT(heights.chosen.loss, heights.assetLoss);
}

// The limit surface passes through the decimated vertices: the initial cage's first step.
// Without the interpolation the Catmull-Clark surface shrinks well inside them. (The limit fit
// that follows trades exactness at the vertices for the whole faces: limit_fit_test.cpp.)
TEST(SimplifyInitialCage, LimitSurfaceInterpolatesTheDecimatedVertices) {
    const mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.15f, 9);
    const mesh::PolygonMesh raw =
        initialCage(reference, {.faces = 300, .interpolationIterations = 0, .limitFit = {.rounds = 0}});
    const mesh::PolygonMesh cage = initialCage(reference, {.faces = 300, .limitFit = {.rounds = 0}});
    ASSERT_EQ(cage.faceIndices, raw.faceIndices);
    EXPECT_EQ(cage.tags.triangles, mesh::TriangleSubdivision::Smooth);

    auto worstGap = [&](const mesh::PolygonMesh& m) {
        const auto limit = limitPositionsOfVertices(m, m.positions);
        float worst = 0.0f;
        for (size_t v = 0; v < limit.size(); ++v) worst = std::max(worst, glm::length(limit[v] - raw.positions[v]));
        return worst;
    };
    const float before = worstGap(raw), after = worstGap(cage);
    EXPECT_GT(before, 0.01f);
    EXPECT_LT(after, before / 20.0f);
    EXPECT_LT(after, 2e-3f);
}

TEST(SimplifyInitialCage, NonFiniteReferenceIsRefused) {
    mesh::PolygonMesh reference = mesh::makeLumpySphere(2, 0.1f, 1);
    reference.sourcePath = "bad.obj";
    reference.positions[3].x = std::nanf("");
    EXPECT_THROW(initialCage(reference, {.faces = 40}), Error);
}

TEST(SurfaceQueries, HitsBothWaysWithSignedDistance) {
    // The plane z = 0 as two triangles over [−1, 1]².
    const mesh::PolygonMesh plane = mesh::triangulated(mesh::makeQuadGrid(1));
    const geometry::SurfaceQueries queries(plane);
    const auto down = queries.cast({0.2f, 0.3f, 0.5f}, {0.0f, 0.0f, -1.0f}, 1.0f);
    ASSERT_TRUE(down);
    EXPECT_NEAR(down->distance, 0.5f, 1e-6f);
    EXPECT_FALSE(queries.cast({0.2f, 0.3f, 0.5f}, {0.0f, 0.0f, 1.0f}, 1.0f));
    EXPECT_FALSE(queries.cast({0.2f, 0.3f, 0.5f}, {0.0f, 0.0f, -1.0f}, 0.4f));  // beyond maxDistance
    const auto both = queries.castBothWays({0.2f, 0.3f, 0.5f}, {0.0f, 0.0f, 1.0f}, 1.0f);
    ASSERT_TRUE(both);
    EXPECT_NEAR(both->distance, -0.5f, 1e-6f);
    // The barycentrics name the hit point.
    const int* f = &plane.faceIndices[size_t(3 * down->triangle)];
    const glm::vec3 p = (1.0f - down->u - down->v) * plane.positions[size_t(f[0])] +
                        down->u * plane.positions[size_t(f[1])] + down->v * plane.positions[size_t(f[2])];
    EXPECT_NEAR(glm::length(p - glm::vec3(0.2f, 0.3f, 0.0f)), 0.0f, 1e-5f);
}

// A thin slab: the top sheet faces +z, the bottom one −z. From inside, near the bottom, the
// nearest hit is the bottom; asking for a sheet that faces along +z passes through to the top.
TEST(SurfaceQueries, CastFacingPassesThroughSheetsFacingTheOtherWay) {
    mesh::PolygonMesh top = mesh::triangulated(mesh::makeQuadGrid(1)), slab = top;
    for (glm::vec3& p : top.positions) p.z = 0.1f;
    for (glm::vec3& p : slab.positions) p.z = -0.1f;
    for (size_t k = 0; k < slab.faceIndices.size(); k += 3) std::swap(slab.faceIndices[k + 1], slab.faceIndices[k + 2]);
    const int offset = slab.vertexCount();
    slab.positions.insert(slab.positions.end(), top.positions.begin(), top.positions.end());
    for (int i : top.faceIndices) slab.faceIndices.push_back(i + offset);
    slab.faceSizes.insert(slab.faceSizes.end(), top.faceSizes.begin(), top.faceSizes.end());
    const geometry::SurfaceQueries queries(slab);
    ASSERT_LT(queries.triangleNormal(0).z, 0.0f);
    const glm::vec3 origin(0.2f, 0.3f, -0.05f), up(0.0f, 0.0f, 1.0f);
    EXPECT_NEAR(queries.castBothWays(origin, up, 1.0f)->distance, -0.05f, 1e-6f);
    const auto along = queries.castFacing(origin, up, 1.0f, 1.0f);
    ASSERT_TRUE(along);
    EXPECT_NEAR(along->distance, 0.15f, 1e-5f);
    EXPECT_GT(queries.triangleNormal(along->triangle).z, 0.0f);
    EXPECT_NEAR(queries.castFacing(origin, up, 1.0f, -1.0f)->distance, -0.05f, 1e-6f);
    EXPECT_FALSE(queries.castFacing(origin, up, 0.1f, 1.0f));  // the top is beyond reach
    // The bottom is the nearest part (0.05 away): the top, three times as far, is a detour.
    EXPECT_TRUE(queries.reachesNearest(origin, *queries.castFacing(origin, up, 1.0f, -1.0f)));
    EXPECT_FALSE(queries.reachesNearest(origin, *along));
    EXPECT_FALSE(queries.reachesNearest(origin, *along, 0.05f));
    EXPECT_TRUE(queries.reachesNearest(origin, *along, 0.11f));  // a short detour is the same relief
}

// The nearest point, whether it lies inside a triangle, on an edge or at a corner.
TEST(SurfaceQueries, ClosestDistanceIsExact) {
    const mesh::PolygonMesh plane = mesh::triangulated(mesh::makeQuadGrid(4));  // [−1, 1]², z = 0
    const geometry::SurfaceQueries queries(plane);
    EXPECT_NEAR(queries.closestDistance({0.3f, -0.2f, 0.7f}), 0.7f, 1e-6f);            // above a face
    EXPECT_NEAR(queries.closestDistance({1.5f, 0.0f, 0.0f}), 0.5f, 1e-6f);             // beyond an edge
    EXPECT_NEAR(queries.closestDistance({2.0f, 2.0f, 1.0f}), std::sqrt(3.0f), 1e-5f);  // past a corner
}

TEST(SurfaceDistance, ParallelPlanesAreTheirGapApart) {
    mesh::PolygonMesh a = mesh::triangulated(mesh::makeQuadGrid(3)), b = a;
    for (auto& p : b.positions) p.z += 0.1f;
    const auto d = geometry::surfaceDistance(a, b, 2000);
    EXPECT_NEAR(d.chamferL2Squared, 2 * 0.01, 1e-6);
    EXPECT_NEAR(d.meanDistance, 0.1, 1e-6);
    EXPECT_NEAR(d.hausdorff, 0.1, 1e-6);
    EXPECT_NEAR(geometry::surfaceDistance(a, a, 2000).hausdorff, 0.0, 1e-6);
}

// A cage inside a sphere of radius R: every node's height is R minus the limit surface's
// distance from the centre, and the sphere's normal is the limit normal, so the normal map
// stays flat up to the cage's own deviation from a sphere.
TEST(SimplifyBake, SphereHeightsAndNormals) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(4);
    mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(48));
    constexpr float kRadius = 1.05f;
    for (auto& p : sphere.positions) p *= kRadius;
    const auto maps = bakeMaps(cage, sphere, {.resolution = 4});
    ASSERT_EQ(maps.displacement.size(), size_t(maps.layout.nodeCount));
    ASSERT_EQ(maps.normal.size(), 2 * size_t(maps.layout.nodeCount));

    const subdiv::LimitEvaluator limit(cage);
    double worstHeight = 0.0, worstTilt = 0.0;
    for (int f = 0; f < maps.layout.ptexFaceCount; ++f)
        for (int j = 0; j <= 4; ++j)
            for (int i = 0; i <= 4; ++i) {
                const int node = maps.layout.node(f, i, j);
                const auto s = limit.evaluate(f, float(i) / 4.0f, float(j) / 4.0f, cage.positions);
                const float expected = kRadius - glm::length(s.position);
                worstHeight = std::max(worstHeight, double(std::abs(maps.displacement[size_t(node)] - expected)));
                worstTilt = std::max(
                    worstTilt, double(std::hypot(maps.normal[2 * size_t(node)], maps.normal[2 * size_t(node) + 1])));
            }
    EXPECT_LT(worstHeight, 3e-3);  // the reference's own facets and the ray's slant
    EXPECT_LT(worstTilt, 0.1);
    for (float d : maps.displacement) ASSERT_TRUE(std::isfinite(d));
}

// Detail a little finer than a map cell: point samples at the nodes alias it, the heights fitted
// across each cell follow it better (what the decoder draws between nodes is bilinear).
TEST(SimplifyBake, LeastSquaresHeightsLieCloserThanPointSamples) {
    const mesh::PolygonMesh reference = mesh::triangulated(mesh::makeLumpySphere(5, 0.04f, 3, 400, 0.002f, 0.004f));
    const mesh::PolygonMesh cage = initialCage(reference, {.faces = 200});
    auto distance = [&](bool leastSquares) {
        const auto maps =
            bakeMaps(cage, reference,
                     {.effects = {maps::MapKind::Displacement}, .resolution = 3, .leastSquaresHeights = leastSquares});
        for (float d : maps.displacement) EXPECT_TRUE(std::isfinite(d));
        return geometry::surfaceDistance(surface::triangleMesh(surface::tessellate(cage, maps, 6)), reference, 20000)
            .meanDistance;
    };
    const double pointSampled = distance(false), fitted = distance(true);
    EXPECT_LT(fitted, 0.9 * pointSampled) << "point-sampled " << pointSampled << ", least squares " << fitted;
}

// Stripes a little finer than the appearance lattice: node point samples alias them into a
// false pattern as strong as the stripes; values fitted across each cell follow what the lattice
// can hold (about their mean) and lie closer to the texture everywhere between the nodes.
TEST(SimplifyBake, AppearanceFittedAcrossCellsLiesCloserThanPointSamples) {
    mesh::PolygonMesh reference = mesh::triangulated(mesh::makeQuadGrid(32, [](float, float) { return 0.01f; }));
    for (const glm::vec3& p : reference.positions) reference.uvs.push_back({(p.x + 1.0f) / 2.0f, (1.0f - p.y) / 2.0f});
    mesh::Image stripes{.name = "stripes", .width = 64, .height = 64, .rgba = {}};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const auto red = std::uint8_t(std::lround(127.5 + 127.5 * std::sin(2.0 * M_PI * x / 5.0)));
            stripes.rgba.insert(stripes.rgba.end(), {red, 128, 128, 255});
        }
    mesh::Material material = mesh::defaultMaterial();
    material.baseColorTexture.image = 0;
    reference.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{material}, {stripes}});
    reference.faceMaterials.assign(size_t(reference.faceCount()), 0);
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(4);  // nodes every 4 texels, stripes every 5

    auto error = [&](bool acrossCells) {
        const auto maps = bakeAppearance(
            cage, reference, {.effects = {maps::MapKind::BaseColor}, .resolution = 4, .acrossCells = acrossCells});
        const subdiv::LimitEvaluator limit(cage);
        double sum = 0.0;
        int samples = 0;
        for (int f = 0; f < maps.appearanceLayout.ptexFaceCount; ++f)
            for (float v = 0.05f; v < 1.0f; v += 0.1f)
                for (float u = 0.05f; u < 1.0f; u += 0.1f) {
                    const glm::vec3 p = limit.evaluate(f, u, v, cage.positions).position;
                    const float expected =
                        mesh::linearToSrgb(mesh::sampleTexture(*reference.materials, material.baseColorTexture,
                                                               {(p.x + 1.0f) / 2.0f, (1.0f - p.y) / 2.0f}, true)
                                               .r);
                    const float baked = surface::sampleBilinear(maps.appearanceLayout, maps.baseColor, 3, 0, f, u, v);
                    EXPECT_TRUE(std::isfinite(baked));
                    sum += double(baked - expected) * double(baked - expected);
                    ++samples;
                }
        return std::sqrt(sum / samples);
    };
    const double pointSampled = error(false), fitted = error(true);
    std::printf("RMS red error: point-sampled %.4f, fitted %.4f\n", pointSampled, fitted);
    EXPECT_LT(fitted, 0.85 * pointSampled) << "RMS red error: point-sampled " << pointSampled << ", fitted " << fitted;
}

TEST(SimplifyBake, OnlyTheAskedMapsAreBaked) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    const mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(8));
    const auto heights = bakeMaps(cage, sphere, {.effects = {maps::MapKind::Displacement}, .resolution = 2});
    EXPECT_TRUE(heights.hasDisplacement());
    EXPECT_FALSE(heights.hasNormal());
    const auto normals = bakeMaps(cage, sphere, {.effects = {maps::MapKind::NormalMap}, .resolution = 2});
    EXPECT_FALSE(normals.hasDisplacement());
    EXPECT_TRUE(normals.hasNormal());
}

// The CPU stages of simplify repeat bit for bit (fresh Embree scenes included), so two runs of
// one seed can differ only through the GPU (docs/architecture.md, Determinism).
TEST(SimplifyDeterminism, InitialCageBakeAndDistanceRepeatExactly) {
    const mesh::PolygonMesh reference = mesh::triangulated(mesh::makeLumpySphere(4, 0.15f, 4));
    const mesh::PolygonMesh cage = initialCage(reference, {.faces = 80});
    EXPECT_EQ(initialCage(reference, {.faces = 80}).positions, cage.positions);
    EXPECT_EQ(initialCage(reference, {.faces = 80}).faceIndices, cage.faceIndices);

    const BakeOptions options{.effects = {maps::MapKind::Displacement, maps::MapKind::NormalMap}, .resolution = 3};
    const auto first = bakeMaps(cage, reference, options), second = bakeMaps(cage, reference, options);
    EXPECT_EQ(first.displacement, second.displacement);
    EXPECT_EQ(first.normal, second.normal);

    const auto a = geometry::surfaceDistance(cage, reference, 20000),
               b = geometry::surfaceDistance(cage, reference, 20000);
    EXPECT_EQ(a.chamferL2Squared, b.chamferL2Squared);
    EXPECT_EQ(a.hausdorff, b.hausdorff);
}

// The budget search bakes a cage's first rung ahead on a thread of its own: the maps it waits for
// are the ones a bake on the spot gives, and a resolution not started ahead is baked when asked.
TEST(SimplifyDeterminism, BakesStartedAheadEqualBakesOnTheSpot) {
    const mesh::PolygonMesh reference = mesh::triangulated(mesh::makeLumpySphere(4, 0.15f, 4));
    const mesh::PolygonMesh cage = initialCage(reference, {.faces = 80});
    const BakeOptions ahead{.effects = {maps::MapKind::Displacement}, .resolution = 3};
    const BakeOptions later{.effects = {maps::MapKind::Displacement}, .resolution = 2};
    CageBakes bakes(cage, reference);
    bakes.startAhead(0, ahead);
    EXPECT_EQ(bakes.at(0, ahead).displacement, bakeMaps(cage, reference, ahead).displacement);
    EXPECT_EQ(bakes.at(0, later).displacement, bakeMaps(cage, reference, later).displacement);
    EXPECT_EQ(&bakes.at(0, ahead), &bakes.at(0, ahead));  // baked once
}

TEST(SimplifyBatch, ShardsParseAndRefuse) {
    const Shard s = parseShard("2/5");
    EXPECT_EQ(s.index, 2);
    EXPECT_EQ(s.count, 5);
    for (const char* bad : {"5/5", "-1/3", "1/0", "1", "a/b", "1/2x", ""}) EXPECT_THROW(parseShard(bad), Error) << bad;
}

}  // namespace
}  // namespace subdfit::simplify
