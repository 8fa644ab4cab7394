// What the viewer draws of a shipped asset.subd (fit::ShippedAsset, the GPU tessellation of the
// decoded cage and its maps) is the surface `subdfit decode` writes (surface::tessellate of the
// same decoded asset): their depth buffers agree at fixed cameras. A decode that dropped the
// heights must not pass the same comparison, or the test could not tell.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "export/engine/subd_decode.h"
#include "codec/subd_format.h"
#include "fit/shipped_asset.h"
#include "gl_test_context.h"
#include "mesh/mesh_loader.h"
#include "render/camera.h"
#include "render/mesh_renderer.h"
#include "render/render_target.h"
#include "scene/scene_frame.h"
#include "surface/tessellation.h"
#include "test_paths.h"

namespace subdfit::fit {
namespace {

constexpr int kResolution = 160;
constexpr int kSegments = 64;  // both sides (the GPU most), so the chords of either are far below the heights

// An asset as `simplify` ships it: `cage` (world units) with bumpy heights on a T = 4 lattice,
// through the encoder and back.
codec::SubdAsset shippedBumps(const mesh::PolygonMesh& cage) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, 4);
    maps.displacement.resize(size_t(maps.layout.nodeCount));
    const float scale = 1.0f / scene::frameAround(cage.positions).scale;  // the cage's radius
    for (size_t i = 0; i < maps.displacement.size(); ++i)
        maps.displacement[i] = 0.04f * scale * std::sin(1.7f * float(i));
    const auto bytes = codec::encodeSubd(codec::shippableAsset(cage, maps));
    return codec::decodeSubd(bytes, "bumps.subd");
}

// Eye-space distance of each covered pixel (negative: background).
std::vector<float> eyeDepth(const render::RenderTarget& target, const render::Camera& camera) {
    std::vector<float> depth = target.readDepth();
    const glm::mat4& p = camera.projection;
    for (float& d : depth) d = d >= 1.0f ? -1.0f : p[3][2] / ((2.0f * d - 1.0f) + p[2][2]);
    return depth;
}

struct Agreement {
    double covered = 0, coverageMismatch = 0, depthMismatch = 0;  // pixels
};

// How far the decoded surface's depth is from the drawn one's at each camera.
Agreement compare(ShippedAsset& drawn, const surface::Tessellation& decoded, const scene::SceneFrame& frame) {
    const auto positions = frame.toNormalized(decoded.positions);
    const render::MeshRenderer triangles(positions, decoded.normals,
                                         std::vector<unsigned>(decoded.indices.begin(), decoded.indices.end()));
    render::RenderTarget gpu(kResolution, kResolution), cpu(kResolution, kResolution);
    Agreement a;
    for (const auto& camera : render::orbitCameras(3, 7)) {
        drawn.draw(camera, gpu);
        triangles.draw(test::programs(), camera, cpu);
        const auto g = eyeDepth(gpu, camera), c = eyeDepth(cpu, camera);
        for (size_t i = 0; i < g.size(); ++i) {
            if (g[i] < 0 && c[i] < 0) continue;
            ++a.covered;
            if ((g[i] < 0) != (c[i] < 0)) ++a.coverageMismatch;
            else if (std::abs(g[i] - c[i]) > 2e-3f) ++a.depthMismatch;  // the frame's radius is 1
        }
    }
    return a;
}

class ShippedAssetDepth : public testing::TestWithParam<std::string> {};

TEST_P(ShippedAssetDepth, TheDrawnSurfaceIsTheDecodedOne) {
    const codec::SubdAsset asset = shippedBumps(mesh::loadMesh(test::assetPath("osd-shapes/" + GetParam())));
    const scene::SceneFrame frame = scene::frameAround(asset.cage.positions);
    ShippedAsset drawn(test::programs(), asset, frame, render::ShadingModel::Geometry, kSegments);
    ASSERT_EQ(drawn.fitter().renderer().tessLevel(), kSegments);

    const Agreement same = compare(drawn, surface::tessellate(asset.cage, asset.maps, kSegments), frame);
    std::printf("%s: %.0f pixels covered, coverage differs on %.0f, depth on %.0f\n", GetParam().c_str(), same.covered,
                same.coverageMismatch, same.depthMismatch);
    ASSERT_GT(same.covered, 0.05 * 3 * kResolution * kResolution);
    EXPECT_LT(same.coverageMismatch, 0.01 * same.covered);  // silhouette pixels
    EXPECT_LT(same.depthMismatch, 0.01 * same.covered);

    surface::SurfaceMaps flat = asset.maps;
    flat.displacement.clear();
    const Agreement without = compare(drawn, surface::tessellate(asset.cage, flat, kSegments), frame);
    std::printf("  without heights: coverage differs on %.0f, depth on %.0f\n", without.coverageMismatch,
                without.depthMismatch);
    EXPECT_GT(without.coverageMismatch + without.depthMismatch, 0.2 * without.covered);
    test::expectNoGlError();
}

// Quads and extraordinary vertices; semi-sharp creases; triangles (ptex sub-faces); a boundary.
INSTANTIATE_TEST_SUITE_P(Cages, ShippedAssetDepth,
                         testing::Values("catmark_cube.obj", "catmark_cube_creases1.obj",
                                         "catmark_pyramid_creases0.obj", "catmark_flap.obj"),
                         [](const auto& info) {
                             std::string name = info.param.substr(0, info.param.find('.'));
                             for (char& c : name)
                                 if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                             return name;
                         });

}  // namespace
}  // namespace subdfit::fit
