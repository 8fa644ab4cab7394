// The bake route's baseline: its asset.subd drawn and measured as subdfit's is, unless that very
// file (byte for byte, drawn with the same segments) was scored already: a fit that kept its
// bake ships it, and its scores are the baseline's.
#include <gtest/gtest.h>

#include <fstream>

#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "scene_fixture.h"
#include "simplify/cage/initial_cage.h"
#include "simplify/compare/baselines.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

TEST(BakeBaseline, AFileScoredAlreadyIsNotDrawnAgainAndAnyOtherIs) {
    const auto dir = scratchDir("bake_baseline_scored");
    fit::FitOptions o = smallFitOptions(dir, 10);
    o.maps = {maps::MapKind::Displacement};
    const mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.1f, 3, 40);
    fit::FitScene scene(fit::resolved(o), programs(), simplify::initialCage(reference, {.faces = 120}), reference);
    const simplify::BakeRoute route{
        .cage = scene.cage, .effects = {maps::MapKind::Displacement}, .resolution = 2, .bits = 8};
    const simplify::BaselineSettings settings{.dir = dir / "baselines", .surfaceSamples = 2000, .segments = 4};

    const simplify::Quality drawn = simplify::bakeBaseline(programs(), scene, route, settings);
    ASSERT_TRUE(drawn.distance.has_value());
    EXPECT_GT(drawn.psnrHoldout, 20.0);
    const std::filesystem::path baked = settings.dir / "bake" / "asset.subd";
    const std::filesystem::path same = dir / "same.subd";
    std::filesystem::copy_file(baked, same);

    // Scores no render could give: where they come back, nothing was drawn.
    simplify::Quality scored;
    scored.psnrHoldout = 123.0;
    scored.ssimHoldout = 0.5;
    scored.psnrViews = {123.0};
    scored.distance = geometry::SurfaceDistance{.meanDistance = 7.0};
    const simplify::Quality reused =
        simplify::bakeBaseline(programs(), scene, route, settings, simplify::ScoredFile{same, scored, 4});
    EXPECT_EQ(reused.psnrHoldout, 123.0);
    EXPECT_EQ(reused.psnrViews, scored.psnrViews);
    ASSERT_TRUE(reused.distance.has_value());
    EXPECT_EQ(reused.distance->meanDistance, 7.0);
    EXPECT_EQ(reused.bytes, drawn.bytes);

    // Other segments, or another file (one byte changed): drawn, as the first time.
    const simplify::Quality otherSegments =
        simplify::bakeBaseline(programs(), scene, route, settings, simplify::ScoredFile{same, scored, 8});
    EXPECT_EQ(otherSegments.psnrHoldout, drawn.psnrHoldout);
    {
        std::fstream file(same, std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(-1, std::ios::end);
        file.put('\x5a');
    }
    const simplify::Quality otherFile =
        simplify::bakeBaseline(programs(), scene, route, settings, simplify::ScoredFile{same, scored, 4});
    EXPECT_EQ(otherFile.psnrHoldout, drawn.psnrHoldout);
    ASSERT_TRUE(otherFile.distance.has_value());
    EXPECT_EQ(otherFile.distance->meanDistance, drawn.distance->meanDistance);
    expectNoGlError();
}

}  // namespace
}  // namespace subdfit::test
