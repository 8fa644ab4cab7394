// A supersampled target set shows what a viewer shows: each pixel the mean of its block of
// samples, for the targets and for whatever is scored against them.
#include <gtest/gtest.h>

#include <cmath>

#include "fit/image_metrics.h"
#include "gl_test_context.h"
#include "mesh/mesh_loader.h"
#include "render/mesh_renderer.h"
#include "scene/scene_frame.h"
#include "scene/target_set.h"
#include "test_paths.h"

namespace subdfit::scene {
namespace {

TEST(TargetSet, ASupersampledPixelIsTheMeanOfItsBlockOfSamples) {
    constexpr int kResolution = 48, kFactor = 4, kFine = kResolution * kFactor;
    mesh::PolygonMesh spot = mesh::triangulated(mesh::loadMesh(test::assetPath("spot/spot_control_mesh.obj")));
    spot.positions = frameAround(spot.positions).toNormalized(spot.positions);
    const render::MeshRenderer renderer(spot.positions, mesh::vertexNormals(spot),
                                        std::vector<unsigned>(spot.faceIndices.begin(), spot.faceIndices.end()));
    gl::ProgramCache& programs = test::programs();
    const TargetSet targets(programs, renderer, render::orbitCameras(2, 1), kResolution, kFactor);

    std::vector<glm::vec4> samples;
    const std::vector<glm::vec4> filtered =
        targets.render(1, [&](const render::Camera& camera, const render::RenderTarget& canvas) {
            renderer.draw(programs, camera, canvas);
            samples = canvas.readColor();
        });
    ASSERT_EQ(samples.size(), size_t(kFine) * kFine);
    ASSERT_EQ(filtered.size(), size_t(kResolution) * kResolution);
    int partial = 0;  // pixels on an outline: some samples on Spot, some on the background
    for (int y = 0; y < kResolution; ++y)
        for (int x = 0; x < kResolution; ++x) {
            glm::vec4 mean(0.0f);
            int covered = 0;
            for (int j = 0; j < kFactor; ++j)
                for (int i = 0; i < kFactor; ++i) {
                    const glm::vec4& s = samples[size_t(y * kFactor + j) * kFine + size_t(x * kFactor + i)];
                    mean += s / float(kFactor * kFactor);
                    covered += s != samples[0];  // the corner sample is background
                }
            partial += covered > 0 && covered < kFactor * kFactor;
            const glm::vec4& got = filtered[size_t(y) * kResolution + size_t(x)];
            for (int c = 0; c < 4; ++c) ASSERT_NEAR(got[c], mean[c], 1e-6f) << "pixel " << x << "," << y;
        }
    EXPECT_GT(partial, kResolution);  // the outline is anti-aliased
    // The target of that view was made the same way.
    EXPECT_EQ(targets.readColor(1), filtered);
    test::expectNoGlError();
}

// loss() is computed on the GPU: it must be the mean pixel loss of what render() returns against
// the target, single-sampled and supersampled, for a drawing that differs from the target.
TEST(TargetSet, ALossIsTheMeanPixelLossOfTheFilteredRender) {
    constexpr int kResolution = 40;  // not a multiple of the work groups' 16 pixels
    mesh::PolygonMesh spot = mesh::triangulated(mesh::loadMesh(test::assetPath("spot/spot_control_mesh.obj")));
    spot.positions = frameAround(spot.positions).toNormalized(spot.positions);
    const std::vector<unsigned> triangles(spot.faceIndices.begin(), spot.faceIndices.end());
    const render::MeshRenderer renderer(spot.positions, mesh::vertexNormals(spot), triangles);
    std::vector<glm::vec3> moved = spot.positions;
    for (glm::vec3& p : moved) p = 0.9f * p + glm::vec3(0.05f, 0.0f, 0.0f);
    const render::MeshRenderer other(moved, mesh::vertexNormals(spot), triangles);
    gl::ProgramCache& programs = test::programs();
    const auto drawOther = [&](const render::Camera& camera, const render::RenderTarget& canvas) {
        other.draw(programs, camera, canvas);
    };
    for (int factor : {1, 4}) {
        const TargetSet targets(programs, renderer, render::orbitCameras(3, 2), kResolution, factor);
        for (int i = 0; i < targets.size(); ++i) {
            const double expected = fit::meanPixelLoss(targets.render(i, drawOther), targets.readColor(i));
            ASSERT_GT(expected, 1e-4);
            EXPECT_NEAR(targets.loss(i, drawOther), expected, 1e-5 * expected) << "factor " << factor << ", view " << i;
            EXPECT_EQ(
                targets.loss(i, [&](const render::Camera& camera,
                                    const render::RenderTarget& canvas) { renderer.draw(programs, camera, canvas); }),
                0.0)
                << "the target drawn again";
        }
    }
    test::expectNoGlError();
}

}  // namespace
}  // namespace subdfit::scene
