// The reference's shading normals carried to the cage through the atlas: the frame a normal
// texture is applied in does not depend on how it is measured, and a cage whose surface bends
// away from the reference shades, through the rewritten texture, with the reference's normals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "mesh/procedural.h"
#include "plain_texture.h"
#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/atlas_shading_normals.h"
#include "surface/displaced_surface.h"

namespace subdfit {
namespace {

constexpr float kDegrees = 180.0f / std::numbers::pi_v<float>;

float angle(glm::vec3 a, glm::vec3 b) {
    return std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0f, 1.0f)) * kDegrees;
}

TEST(NormalTextureFrame, IsTheTextureCoordinatesGradientsWhicheverTangentsMeasureThem) {
    // A plane z = 0 textured as glTF maps an image onto it: u along +x, v down the image (−y).
    const glm::vec3 n(0, 0, 1);
    const auto frame = simplify::normalTextureFrame({1, 0, 0}, {0, 1, 0}, {0.5f, 0}, {0, -0.5f}, n);
    ASSERT_TRUE(frame);
    // Red tilts towards +u, green up the image (+y here), blue along the normal.
    EXPECT_LT(glm::distance((*frame)[0], glm::vec3(1, 0, 0)), 1e-6f);
    EXPECT_LT(glm::distance((*frame)[1], glm::vec3(0, 1, 0)), 1e-6f);
    EXPECT_LT(glm::distance((*frame)[2], n), 1e-6f);
    // Other tangents of the same plane, in the other order, give the same frame.
    const glm::vec3 a(0.3f, 0.7f, 0), b(-0.9f, 0.2f, 0);
    auto uvOf = [](glm::vec3 d) { return glm::vec2(0.5f * d.x, -0.5f * d.y); };
    const auto again = simplify::normalTextureFrame(b, a, uvOf(b), uvOf(a), n);
    ASSERT_TRUE(again);
    for (int c = 0; c < 3; ++c) EXPECT_LT(glm::distance((*again)[c], (*frame)[c]), 1e-5f);
    // Coordinates that do not change across the surface give none.
    EXPECT_FALSE(simplify::normalTextureFrame({1, 0, 0}, {0, 1, 0}, {0, 0}, {0, 0}, n));
    EXPECT_FALSE(simplify::normalTextureFrame({1, 0, 0}, {2, 0, 0}, {0.5f, 0}, {1, 0}, n));
}

// A flat reference (the plane [−1, 1]², 32 × 32 quads as triangles) textured through its own
// coordinates, whose author tilted its normals by `tilt` (a glTF viewer shades that, not the
// plane's own normal); a white base colour texture makes it suitable for an atlas.
mesh::PolygonMesh tiltedPlane(glm::vec3 (*tilt)(glm::vec3 p)) {
    const mesh::PolygonMesh quads = mesh::makeQuadGrid(32);
    mesh::PolygonMesh reference = quads;
    reference.faceSizes.clear();
    reference.faceIndices.clear();
    for (size_t f = 0; f < quads.faceSizes.size(); ++f) {
        const int* q = &quads.faceIndices[4 * f];
        reference.faceIndices.insert(reference.faceIndices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
        reference.faceSizes.insert(reference.faceSizes.end(), {3, 3});
    }
    for (const glm::vec3& p : reference.positions) {
        reference.uvs.push_back({(p.x + 1.0f) / 2.0f, (1.0f - p.y) / 2.0f});
        reference.normals.push_back(glm::normalize(tilt(p)));
    }
    test::paintWhite(reference);
    return reference;
}

// The normal the renderer shades the cage with at ptex (u, v) of `face` (glsl/patch.frag's
// atlasMappedNormal): the texture bilinear between texel centres, in the surface's frame.
glm::vec3 shadedNormal(const surface::DisplacedSurface& surface, const surface::SurfaceMaps& maps, int face, float u,
                       float v, glm::vec3 facing = glm::vec3(0, 0, 1)) {
    const surface::SurfaceVertex p = surface.at(face, u, v);
    const float h = 1e-3f;
    const glm::vec2 duv1 = (surface::atlasUvAt(maps.appearanceAtlas, face, u + h, v) -
                            surface::atlasUvAt(maps.appearanceAtlas, face, u - h, v)) /
                           (2 * h);
    const glm::vec2 duv2 = (surface::atlasUvAt(maps.appearanceAtlas, face, u, v + h) -
                            surface::atlasUvAt(maps.appearanceAtlas, face, u, v - h)) /
                           (2 * h);
    const glm::vec3 n =
        glm::dot(p.normal, facing) < 0.0f ? -p.normal : p.normal;  // seen from the side the author faces
    const auto frame = simplify::normalTextureFrame(p.dPdu, p.dPdv, duv1, duv2, n);
    if (!frame) return n;
    const int size = maps.appearanceAtlas.size;
    const glm::vec2 at =
        glm::clamp(surface::atlasUvAt(maps.appearanceAtlas, face, u, v) * float(size) - 0.5f, 0.0f, float(size - 1));
    const int i = std::min(int(at.x), size - 2), j = std::min(int(at.y), size - 2);
    const float a = at.x - float(i), b = at.y - float(j);
    auto texel = [&](int x, int y) {
        const float* t = &maps.normalTexture[3 * (size_t(y) * size_t(size) + size_t(x))];
        return glm::vec3(t[0], t[1], t[2]) * 2.0f - 1.0f;
    };
    const glm::vec3 t =
        glm::mix(glm::mix(texel(i, j), texel(i + 1, j), a), glm::mix(texel(i, j + 1), texel(i + 1, j + 1), a), b);
    return glm::normalize(*frame * t);
}

struct AngleStats {
    float mean = 0.0f, worst = 0.0f;
};

// Over the inner faces of a 4 × 4 cage (the boundary's limit surface curls), the angle between
// the cage's shaded normal and the reference's at the same point of the plane.
template <class Expected>
AngleStats compare(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps, Expected expected) {
    const surface::DisplacedSurface surface(cage, maps);
    AngleStats s;
    int count = 0;
    for (int f = 0; f < surface.ptexFaceCount(); ++f) {
        if (f % 4 == 0 || f % 4 == 3 || f / 4 == 0 || f / 4 == 3) continue;
        for (float v = 0.1f; v < 1.0f; v += 0.2f)
            for (float u = 0.1f; u < 1.0f; u += 0.2f) {
                const glm::vec2 uv = surface::atlasUvAt(maps.appearanceAtlas, f, u, v);
                const float a = angle(shadedNormal(surface, maps, f, u, v),
                                      expected(glm::vec3(2.0f * uv.x - 1.0f, 1.0f - 2.0f * uv.y, 0.0f)));
                s.mean += a, s.worst = std::max(s.worst, a), ++count;
            }
    }
    s.mean /= float(count);
    return s;
}

TEST(AtlasShadingNormals, ABulgingCageShadesAsTheFlatReferenceItStandsFor) {
    // The cage bulges up to 0.25 over the plane: its own normals lean up to ~25°.
    const mesh::PolygonMesh reference = tiltedPlane([](glm::vec3) { return glm::vec3(0, 0, 1); });
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(4, [](float x, float y) {
        return 0.25f * std::cos(0.5f * std::numbers::pi_v<float> * x) * std::cos(0.5f * std::numbers::pi_v<float> * y);
    });
    auto up = [](glm::vec3) { return glm::vec3(0, 0, 1); };
    const surface::SurfaceMaps plain =
        simplify::bakeAtlasAppearance(cage, reference, {maps::MapKind::BaseColor}, 16, 0.5f, false);
    ASSERT_TRUE(plain.normalTexture.empty());  // the reference has no normal texture
    surface::SurfaceMaps flat = plain;
    flat.normalTexture.assign(3 * 16 * 16, 0.5f);
    for (size_t t = 0; t < 16 * 16; ++t) flat.normalTexture[3 * t + 2] = 1.0f;
    const AngleStats before = compare(cage, flat, up);
    const surface::SurfaceMaps carried =
        simplify::bakeAtlasAppearance(cage, reference, {maps::MapKind::BaseColor}, 16, 0.5f, true);
    ASSERT_EQ(carried.normalTexture.size(), 3u * 16 * 16);
    const AngleStats after = compare(cage, carried, up);
    std::printf("shading normal error: %.2f° mean, %.2f° worst before; %.2f°, %.2f° carried\n", before.mean,
                before.worst, after.mean, after.worst);
    EXPECT_GT(before.mean, 8.0f);
    EXPECT_LT(after.mean, 1.0f);
    EXPECT_LT(after.worst, 3.0f);
}

TEST(AtlasShadingNormals, ACageOnTheReferenceTakesItsAuthorsTiltedNormals) {
    // The author's normals lean up to ~17° in a pattern the flat cage knows nothing of.
    auto tilt = [](glm::vec3 p) { return glm::vec3(0.3f * std::sin(1.5f * p.x), 0.2f * std::cos(2.0f * p.y), 1.0f); };
    const mesh::PolygonMesh reference = tiltedPlane(tilt);
    const mesh::PolygonMesh cage = mesh::makeQuadGrid(4);
    const surface::SurfaceMaps carried =
        simplify::bakeAtlasAppearance(cage, reference, {maps::MapKind::BaseColor}, 16, 0.5f, true);
    const AngleStats after = compare(cage, carried, tilt);
    std::printf("shading normal error: %.2f° mean, %.2f° worst\n", after.mean, after.worst);
    EXPECT_LT(after.mean, 1.0f);
    EXPECT_LT(after.worst, 3.0f);
}

}  // namespace
}  // namespace subdfit
