// The reference's shading normals carried through the atlas, as the GPU draws them: a reference
// that is the cage's own limit surface, its author's normals tilted away from the surface's,
// renders much like the cage with the carried normal texture and unlike it without.
#include <gtest/gtest.h>

#include <cmath>

#include "fit/fit_run.h"
#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "plain_texture.h"
#include "scene_fixture.h"
#include "simplify/bake/atlas_bake.h"
#include "surface/tessellation.h"

namespace subdfit::test {
namespace {

// `cage`'s limit surface as triangles, each ptex face textured on a tile of its own (a 5 × 5
// grid of tiles with gutters) through a white base colour texture, its normals tilted by a
// smooth field up to ~`tilt` radians.
mesh::PolygonMesh tiledLimitSurface(const mesh::PolygonMesh& cage, float tilt) {
    const surface::Tessellation t = surface::tessellate(cage, {}, 8);
    mesh::PolygonMesh reference = surface::triangleMesh(t);
    for (size_t i = 0; i < t.vertexCount(); ++i) {
        const surface::PtexPoint& p = t.ptex[i];
        const glm::vec2 tile(float(p.face % 5), float(p.face / 5));
        reference.uvs.push_back((tile + 0.1f + 0.8f * glm::vec2(p.u, p.v)) / 5.0f);
        const glm::vec3 x = t.positions[i], n = t.normals[i];
        const glm::vec3 field(std::sin(3.0f * x.y), std::cos(2.0f * x.z), std::sin(2.5f * x.x));
        reference.normals.push_back(glm::normalize(n + tilt * (field - glm::dot(field, n) * n)));
    }
    paintWhite(reference);
    return reference;
}

// The image loss of `cage` with its atlas baked from `reference`, the reference's normals
// carried or not, against the reference's Lambert renders from 4 views.
double atlasLoss(const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference, bool carried) {
    gl::ProgramCache& cache = programs();
    const render::MeshRenderer renderer(reference, render::ShadingModel::Lambert);
    const scene::TargetSet targets(cache, renderer, render::orbitCameras(4, 2), 96);
    const surface::SurfaceMaps maps =
        simplify::bakeAtlasAppearance(cage, reference, {maps::MapKind::BaseColor}, 64, 0.3f, carried);
    EXPECT_EQ(maps.normalTexture.empty(), !carried);
    fit::CageFitSettings settings;
    settings.resolution = 96;
    settings.shading = render::ShadingModel::Lambert;
    settings.mapEffects = {maps::MapKind::BaseColor};
    settings.maps.appearanceAtlas = 64;
    fit::CageFitter fitter(cache, cage, settings);
    fit::writeMaps(fitter, maps);
    const double loss = totalLoss(fitter, targets);
    return loss;
}

TEST(AtlasShadingNormals, TheCarriedTextureMakesTheCageShadeAsTheReference) {
    mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    const auto frame = scene::frameAround(cage.positions);
    cage.positions = frame.toNormalized(cage.positions);
    ASSERT_LE(cage.faceCount(), 25);
    const mesh::PolygonMesh tilted = tiledLimitSurface(cage, 0.5f), plain = tiledLimitSurface(cage, 0.0f);
    const double own = atlasLoss(cage, tilted, false), carried = atlasLoss(cage, tilted, true);
    const double untilted = atlasLoss(cage, plain, false);
    std::printf(
        "image loss against tilted normals: %.4g with the cage's own, %.4g carried (%.4g against its own normals)\n",
        own, carried, untilted);
    EXPECT_LT(carried, 0.25 * own);
}

}  // namespace
}  // namespace subdfit::test
