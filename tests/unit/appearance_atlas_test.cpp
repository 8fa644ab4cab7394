// The appearance in the reference's own texture atlas: the bake gives every surface point the
// reference's texture coordinates there (and keeps the two sides of a seam apart), the AUVS
// section and the .subd file carry the corners' coordinates within their quantisation step, and
// a damaged section is refused; the shipped surface's TANGENTs follow the atlas.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include <glm/geometric.hpp>

#include <zstd.h>

#include "codec/atlas_uv_coding.h"
#include "codec/subd_format.h"
#include "mesh/procedural.h"
#include "simplify/bake/atlas_bake.h"
#include "subdiv/limit_evaluator.h"
#include "surface/appearance_atlas.h"
#include "surface/tessellation.h"
#include "util/error.h"

namespace subdfit {
namespace {

using Rgba = std::array<std::uint8_t, 4>;
Rgba gradient(int x, int y) { return {std::uint8_t(x * 4), std::uint8_t(y * 4), 128, 255}; }

// One material whose base colour is a 64² texture: `texel` (x, y), by default red along u and
// green along v.
void paint(mesh::PolygonMesh& reference, Rgba (*texel)(int x, int y) = gradient) {
    mesh::Image image{.name = "painted", .width = 64, .height = 64, .rgba = {}};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const Rgba c = texel(x, y);
            image.rgba.insert(image.rgba.end(), c.begin(), c.end());
        }
    mesh::Material m = mesh::defaultMaterial();
    m.baseColorTexture.image = 0;
    reference.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{m}, {image}});
    reference.faceMaterials.assign(size_t(reference.faceCount()), 0);
}

mesh::PolygonMesh triangles(const mesh::PolygonMesh& quads) {
    mesh::PolygonMesh out = quads;
    out.faceSizes.clear();
    out.faceIndices.clear();
    size_t offset = 0;
    for (int n : quads.faceSizes) {
        for (int k = 1; k + 1 < n; ++k) {
            out.faceIndices.insert(out.faceIndices.end(),
                                   {quads.faceIndices[offset], quads.faceIndices[offset + size_t(k)],
                                    quads.faceIndices[offset + size_t(k) + 1]});
            out.faceSizes.push_back(3);
        }
        offset += size_t(n);
    }
    return out;
}

// Ptex points of every face of `cage` (a 3 × 3 grid in each), with their limit positions.
template <class Check>
void forSurfacePoints(const mesh::PolygonMesh& cage, Check check) {
    const subdiv::LimitEvaluator limit(cage);
    for (int f = 0; f < limit.ptexFaceCount(); ++f)
        for (float v : {0.1f, 0.5f, 0.9f})
            for (float u : {0.1f, 0.5f, 0.9f}) check(f, u, v, limit.evaluate(f, u, v, cage.positions).position);
}

TEST(AtlasBake, APlaneGetsItsOwnTextureCoordinatesAndTexture) {
    mesh::PolygonMesh reference = triangles(mesh::makeQuadGrid(32));
    for (const glm::vec3& p : reference.positions) reference.uvs.push_back({(p.x + 1.0f) / 2.0f, (1.0f - p.y) / 2.0f});
    paint(reference);
    ASSERT_EQ(simplify::atlasUnsuitability(reference), "");
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(4);
    const surface::SurfaceMaps maps = simplify::bakeAtlasAppearance(cage, reference, {maps::MapKind::BaseColor}, 16);
    ASSERT_TRUE(maps.appearanceAtlas.present());
    ASSERT_EQ(maps.baseColor.size(), 3u * 16 * 16);
    // Inside, the limit surface of a uniform grid is parametrised linearly, and bilinear corners
    // give it exactly; the boundary faces' limit parametrisation bends (boundary rules), which
    // bilinear corners follow to within a small part of the face.
    float worstInside = 0.0f, worst = 0.0f;
    forSurfacePoints(cage, [&](int f, float u, float v, glm::vec3 p) {
        const glm::vec2 expected((p.x + 1.0f) / 2.0f, (1.0f - p.y) / 2.0f);
        const float error = glm::distance(surface::atlasUvAt(maps.appearanceAtlas, f, u, v), expected);
        worst = std::max(worst, error);
        if (f % 4 != 0 && f % 4 != 3 && f / 4 != 0 && f / 4 != 3) worstInside = std::max(worstInside, error);
    });
    std::printf("texture coordinate error: %.4g inside, %.4g on boundary faces (a face spans 0.25)\n", worstInside,
                worst);
    EXPECT_LT(worstInside, 1e-3f);
    EXPECT_LT(worst, 0.25f * 0.1f);
    // The texels are the texture downscaled: red grows along a row, green down a column.
    EXPECT_LT(maps.baseColor[3 * 0], maps.baseColor[3 * 15]);
    EXPECT_LT(maps.baseColor[3 * 0 + 1], maps.baseColor[3 * (15 * 16) + 1]);
    EXPECT_NEAR(maps.baseColor[3 * (8 * 16 + 8)], (8.5f * 4.0f * 4.0f - 2.0f) / 255.0f, 0.03f);  // texel 8's mean red
}

TEST(AtlasBake, ChartBordersKeepTheirColourNotTheGutters) {
    // A plane textured through the middle of its image, [0.3, 0.7]², which is orange there and
    // black around: every texel of a coarse atlas is the chart's orange, those its border cuts
    // through and the gutter's too.
    mesh::PolygonMesh reference = triangles(mesh::makeQuadGrid(8));
    for (const glm::vec3& p : reference.positions) reference.uvs.push_back({0.5f + 0.2f * p.x, 0.5f - 0.2f * p.y});
    paint(reference, [](int x, int y) -> Rgba {
        const bool chart = x >= 19 && x < 45 && y >= 19 && y < 45;  // texel centres inside [0.3, 0.7]
        return chart ? Rgba{255, 128, 0, 255} : Rgba{0, 0, 0, 255};
    });
    const surface::SurfaceMaps maps =
        simplify::bakeAtlasAppearance(mesh::makeQuadGrid(2), reference, {maps::MapKind::BaseColor}, 8);
    ASSERT_EQ(maps.baseColor.size(), 3u * 8 * 8);
    for (size_t t = 0; t < 64; ++t) {
        EXPECT_NEAR(maps.baseColor[3 * t], 1.0f, 0.02f) << "texel " << t;
        EXPECT_NEAR(maps.baseColor[3 * t + 1], 128.0f / 255.0f, 0.02f) << "texel " << t;
    }
}

// A tube around z whose texture wraps once around it, its vertices split along the seam at
// angle 0 (u = 0 on one side, 1 on the other), as any exporter writes a cylinder.
mesh::PolygonMesh seamedTube(int around, int along) {
    mesh::PolygonMesh tube;
    for (int j = 0; j <= along; ++j)
        for (int i = 0; i <= around; ++i) {
            const float a = 2.0f * std::numbers::pi_v<float> * float(i) / float(around);
            tube.positions.push_back({std::cos(a), std::sin(a), -1.0f + 2.0f * float(j) / float(along)});
            tube.uvs.push_back({float(i) / float(around), float(j) / float(along)});
        }
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
            const int a = j * (around + 1) + i, b = a + 1, c = a + around + 2, d = a + around + 1;
            tube.faceIndices.insert(tube.faceIndices.end(), {a, b, c, a, c, d});
            tube.faceSizes.insert(tube.faceSizes.end(), {3, 3});
        }
    paint(tube);
    return tube;
}

// The same tube as a closed ring of quads (welded: no seam in the cage).
mesh::PolygonMesh tubeCage(int around, int along) {
    mesh::PolygonMesh cage;
    for (int j = 0; j <= along; ++j)
        for (int i = 0; i < around; ++i) {
            const float a = 2.0f * std::numbers::pi_v<float> * (float(i) + 0.5f) / float(around);
            cage.positions.push_back({std::cos(a), std::sin(a), -0.8f + 1.6f * float(j) / float(along)});
        }
    for (int j = 0; j < along; ++j)
        for (int i = 0; i < around; ++i) {
            const int a = j * around + i, b = j * around + (i + 1) % around;
            cage.faceIndices.insert(cage.faceIndices.end(), {a, b, b + around, a + around});
            cage.faceSizes.push_back(4);
        }
    return cage;
}

TEST(AtlasBake, TheTwoSidesOfASeamKeepTheirOwnCoordinates) {
    const mesh::PolygonMesh reference = seamedTube(96, 8);
    const mesh::PolygonMesh cage = tubeCage(12, 3);
    const surface::SurfaceMaps maps = simplify::bakeAtlasAppearance(cage, reference, {maps::MapKind::BaseColor}, 32);
    // Every surface point reads the texture where the reference has it (u by angle, modulo the
    // wrap: a face across the seam takes one side's coordinates and runs past 1 or below 0).
    float worst = 0.0f;
    forSurfacePoints(cage, [&](int f, float u, float v, glm::vec3 p) {
        const float expected = std::atan2(p.y, p.x) / (2.0f * std::numbers::pi_v<float>);
        const float got = surface::atlasUvAt(maps.appearanceAtlas, f, u, v).x;
        const float wrapped = std::abs(std::remainder(got - expected, 1.0f));
        worst = std::max(worst, wrapped);
    });
    EXPECT_LT(worst, 0.02f);
    // No face spans the atlas (its corners welded across the seam would).
    for (int f = 0; f < cage.faceCount(); ++f) {
        float lo = 2.0f, hi = -2.0f;
        for (int k = 0; k < 4; ++k) {
            lo = std::min(lo, maps.appearanceAtlas.cornerUvs[4 * size_t(f) + size_t(k)].x);
            hi = std::max(hi, maps.appearanceAtlas.cornerUvs[4 * size_t(f) + size_t(k)].x);
        }
        EXPECT_LT(hi - lo, 0.2f) << "face " << f;
    }
}

TEST(AtlasBake, SaysWhyAReferenceCannotKeepItsAtlas) {
    mesh::PolygonMesh reference = seamedTube(8, 2);
    reference.materials = nullptr;
    EXPECT_NE(simplify::atlasUnsuitability(reference), "");
    reference = seamedTube(8, 2);
    reference.uvs[3].x = 1.5f;  // a repeating texture
    EXPECT_NE(simplify::atlasUnsuitability(reference).find("leave [0, 1]"), std::string::npos);
    reference = seamedTube(8, 2);
    reference.uvs.clear();
    EXPECT_NE(simplify::atlasUnsuitability(reference), "");
}

// Corner coordinates that agree at shared corners within a chart, and a seam.
surface::AppearanceAtlas someAtlas(const mesh::PolygonMesh& cage, int size) {
    const subdiv::LimitEvaluator limit(cage);
    surface::AppearanceAtlas atlas{.size = size, .cornerUvs = {}};
    for (int f = 0; f < limit.ptexFaceCount(); ++f) {
        const bool otherChart = f % 3 == 0;
        for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
            const glm::vec3 p = limit.evaluate(f, corner.x, corner.y, cage.positions).position;
            atlas.cornerUvs.push_back(glm::vec2(0.3f + 0.25f * p.x, 0.4f + 0.3f * p.y) +
                                      (otherChart ? glm::vec2(0.5f, 0.0f) : glm::vec2(0.0f)));
        }
    }
    return atlas;
}

// What tiles leave out is named, from the materials the faces use only: the normal texture, and
// the occlusion where no metallic-roughness map can ship it; emission rides along.
TEST(AtlasBake, SaysWhatTilesLeaveOut) {
    mesh::PolygonMesh reference = triangles(mesh::makeQuadGrid(2));
    paint(reference);
    EXPECT_EQ(simplify::lostOnTiles(reference, true), "");  // a base colour texture: tiles carry it
    mesh::MaterialSet set = *reference.materials;
    mesh::Material glowing = set.materials[0];
    glowing.emissiveFactor = {1, 0.5f, 0};
    glowing.normalTexture.image = 0;
    set.materials.push_back(glowing);
    reference.materials = std::make_shared<mesh::MaterialSet>(set);
    EXPECT_EQ(simplify::lostOnTiles(reference, true), "") << "a material no face uses";
    EXPECT_FALSE(simplify::carriedLookOf(reference).emission);
    reference.faceMaterials.back() = 1;
    EXPECT_EQ(simplify::lostOnTiles(reference, true), "normal texture");
    EXPECT_TRUE(simplify::carriedLookOf(reference).emission);
    set.materials[0].occlusionTexture.image = 0;
    reference.materials = std::make_shared<mesh::MaterialSet>(set);
    EXPECT_EQ(simplify::lostOnTiles(reference, true), "normal texture");
    EXPECT_EQ(simplify::lostOnTiles(reference, false), "normal texture, occlusion texture");
    reference.materials = nullptr;
    EXPECT_EQ(simplify::lostOnTiles(reference, false), "");
}

TEST(AtlasUvCoding, RoundTripsWithinTheQuantisationStep) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    const surface::AppearanceAtlas atlas = someAtlas(cage, 128);
    codec::ByteWriter out;
    codec::writeAtlasUvs(cage, atlas, out);
    codec::ByteReader in(out.bytes(), "AUVS");
    const surface::AppearanceAtlas back = codec::readAtlasUvs(in, cage);
    EXPECT_EQ(in.remaining(), 0u);
    ASSERT_EQ(back.size, 128);
    ASSERT_EQ(back.cornerUvs.size(), atlas.cornerUvs.size());
    const float step = std::ldexp(1.0f, -codec::atlasUvBits(128));
    for (size_t k = 0; k < atlas.cornerUvs.size(); ++k)
        EXPECT_LE(glm::distance(back.cornerUvs[k], atlas.cornerUvs[k]), step) << "corner " << k;
    // Shared corners are stored once: fewer than 4 bytes a ptex corner before entropy coding.
    EXPECT_LT(out.bytes().size(), 4 * atlas.cornerUvs.size());

    for (size_t cut : {size_t(1), out.bytes().size() / 2, out.bytes().size() - 1}) {
        codec::ByteReader truncated(std::span(out.bytes()).first(cut), "AUVS");
        EXPECT_THROW(codec::readAtlasUvs(truncated, cage), Error) << "cut at " << cut;
    }
}

// The AUVS section of `atlas` on `cage` as asset.subd stores it (zstd), having checked that it
// round-trips within the quantisation step.
size_t packedAtlasUvs(const mesh::PolygonMesh& cage, const surface::AppearanceAtlas& atlas) {
    codec::ByteWriter out;
    codec::writeAtlasUvs(cage, atlas, out);
    codec::ByteReader in(out.bytes(), "AUVS");
    const surface::AppearanceAtlas back = codec::readAtlasUvs(in, cage);
    const float step = std::ldexp(1.0f, -codec::atlasUvBits(atlas.size));
    for (size_t k = 0; k < atlas.cornerUvs.size(); ++k)
        EXPECT_LE(glm::distance(back.cornerUvs[k], atlas.cornerUvs[k]), step) << "corner " << k;
    std::vector<char> packed(ZSTD_compressBound(out.bytes().size()));
    const size_t bytes = ZSTD_compress(packed.data(), packed.size(), out.bytes().data(), out.bytes().size(), 19);
    EXPECT_FALSE(ZSTD_isError(bytes));
    return bytes;
}

TEST(AtlasUvCoding, ATriangleCagesMidpointsAndCentresArePredicted) {
    // A triangle cage whose vertices have jittered coordinates (8 bits of noise an axis, which no
    // coder can predict), its sub-faces' edge midpoints and centres the means of them, as inside
    // a chart: those cost about the quantisation's rounding, a fraction of what the same values
    // cost jittered on their own.
    const mesh::PolygonMesh cage = triangles(mesh::makeQuadGrid(16));
    constexpr int kSize = 128;
    const float step = std::ldexp(1.0f, -codec::atlasUvBits(kSize));
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> jitter(-128, 127);
    auto noise = [&] { return step * glm::vec2(float(jitter(rng)), float(jitter(rng))); };
    std::vector<glm::vec2> vertexUv;
    for (const glm::vec3& p : cage.positions)
        vertexUv.push_back(glm::vec2(0.5f + 0.4f * p.x, 0.5f + 0.4f * p.y) + noise());
    surface::AppearanceAtlas predictable{.size = kSize, .cornerUvs = {}}, jittered = predictable;
    for (int t = 0; t < cage.faceCount(); ++t) {
        auto uv = [&](int i) { return vertexUv[size_t(cage.faceIndices[size_t(3 * t + (i + 3) % 3)])]; };
        const glm::vec2 centre = (uv(0) + uv(1) + uv(2)) / 3.0f, centreNoise = noise();
        std::vector<glm::vec2> edgeNoise{noise(), noise(), noise()};
        for (int i = 0; i < 3; ++i) {  // sub-face i: (0,0) at vertex i, (1,0) towards i + 1, (0,1) towards i − 1
            const glm::vec2 next = 0.5f * (uv(i) + uv(i + 1)), previous = 0.5f * (uv(i - 1) + uv(i));
            predictable.cornerUvs.insert(predictable.cornerUvs.end(), {uv(i), next, centre, previous});
            jittered.cornerUvs.insert(
                jittered.cornerUvs.end(),
                {uv(i), next + edgeNoise[size_t(i)], centre + centreNoise, previous + edgeNoise[size_t((i + 2) % 3)]});
        }
    }
    const size_t predicted = packedAtlasUvs(cage, predictable), unpredictable = packedAtlasUvs(cage, jittered);
    std::printf("AUVS of %zu vertices, %zu sub-faces: %zu bytes, %zu with jittered midpoints and centres\n",
                cage.positions.size(), predictable.cornerUvs.size() / 4, predicted, unpredictable);
    EXPECT_LT(double(predicted), 0.5 * double(unpredictable));
}

TEST(AtlasUvCoding, TheShippedFileCarriesTheAtlas) {
    mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    surface::SurfaceMaps maps;
    maps.appearanceAtlas = someAtlas(cage, 32);
    maps.appearanceLayout = surface::atlasLattice(32);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.2f, 0.8f);
    for (int k = 0; k < 3 * 32 * 32; ++k) maps.baseColor.push_back(k % 3 == 0 ? float(k % 96) / 96.0f : 0.5f);
    const codec::SubdAsset asset = codec::shippableAsset(cage, maps, 14);
    const auto bytes = codec::encodeSubd(asset);
    const codec::SubdAsset back = codec::decodeSubd(bytes, "atlas.subd");
    ASSERT_TRUE(back.maps.appearanceAtlas.present());
    EXPECT_EQ(back.maps.appearanceLayout.nodeCount, 32 * 32);
    ASSERT_EQ(back.maps.appearanceAtlas.cornerUvs.size(), asset.maps.appearanceAtlas.cornerUvs.size());
    const float step = std::ldexp(1.0f, -codec::atlasUvBits(32));
    for (size_t k = 0; k < back.maps.appearanceAtlas.cornerUvs.size(); ++k)
        ASSERT_LE(glm::distance(back.maps.appearanceAtlas.cornerUvs[k], asset.maps.appearanceAtlas.cornerUvs[k]), step);
    double error = 0.0;
    for (size_t k = 0; k < maps.baseColor.size(); ++k)
        error = std::max(error, double(std::abs(back.maps.baseColor[k] - maps.baseColor[k])));
    EXPECT_LT(error, 0.08);  // JPEG at quality 90
}

// glTF's TANGENT for the carried normal texture: along the atlas's s, with w = +1 where "up the
// image" (against t) is cross(normal, tangent), -1 where the atlas is mirrored.
TEST(AtlasTangent, FollowsTheAtlasCoordinatesAndTheirHandedness) {
    const glm::vec3 n(0, 0, 1), dPdu(2, 0, 0), dPdv(0, 0.5f, 0);
    const glm::vec4 fallback(0, 1, 0, 1);
    // Jacobian columns: the atlas coordinates' change along u and along v.
    const auto tangent = [&](glm::vec2 alongU, glm::vec2 alongV) {
        return surface::atlasTangent(n, dPdu, dPdv, glm::mat2(alongU, alongV), fallback);
    };
    EXPECT_EQ(tangent({0.1f, 0}, {0, -0.1f}), glm::vec4(1, 0, 0, 1));     // s along x, t down the image
    EXPECT_EQ(tangent({-0.1f, 0}, {0, -0.1f}), glm::vec4(-1, 0, 0, -1));  // mirrored in s
    EXPECT_EQ(tangent({0.1f, 0}, {0, 0.1f}), glm::vec4(1, 0, 0, -1));     // mirrored in t
    EXPECT_EQ(tangent({0, 0.1f}, {0.1f, 0}), glm::vec4(0, 1, 0, 1));      // s along y, t along x: turned
    EXPECT_EQ(tangent({0, 0}, {0, 0}), fallback);                         // a face the atlas collapses
    EXPECT_EQ(surface::atlasTangent(n, glm::vec3(0), glm::vec3(0), glm::mat2(1.0f), fallback), fallback);  // a pole
}

TEST(AtlasTangent, TheTessellationCarriesTheAtlasFrame) {
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(4);
    for (const float sense : {1.0f, -1.0f}) {
        surface::SurfaceMaps maps;
        maps.appearanceAtlas = {.size = 64, .cornerUvs = {}};
        const subdiv::LimitEvaluator limit(cage);
        for (int f = 0; f < limit.ptexFaceCount(); ++f)
            for (const glm::vec2 corner : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)}) {
                const glm::vec3 p = limit.evaluate(f, corner.x, corner.y, cage.positions).position;
                maps.appearanceAtlas.cornerUvs.push_back({0.5f + sense * 0.4f * p.x, 0.5f - 0.4f * p.y});
            }
        const surface::Tessellation t = surface::tessellate(cage, maps, 4);
        ASSERT_EQ(t.tangents.size(), t.positions.size());
        for (size_t v = 0; v < t.tangents.size(); ++v) {
            const glm::vec3 tangent(t.tangents[v]);
            ASSERT_NEAR(glm::length(tangent), 1.0f, 1e-5f) << v;
            ASSERT_NEAR(glm::dot(tangent, t.normals[v]), 0.0f, 1e-5f) << v;
            // Inside, the limit surface is the grid's plane affinely in (u, v), as the atlas is;
            // the boundary faces' limit shrinks inwards and bends the blend a little.
            const glm::vec3 p = t.positions[v];
            if (std::max(std::abs(p.x), std::abs(p.y)) < 0.5001f) {
                ASSERT_GT(sense * tangent.x, 0.999f) << v << (sense > 0 ? "" : ", mirrored");
            }
            ASSERT_GT(sense * tangent.x, 0.5f) << v << (sense > 0 ? "" : ", mirrored");
            ASSERT_EQ(t.tangents[v].w, sense) << v;
        }
    }
}

}  // namespace
}  // namespace subdfit
