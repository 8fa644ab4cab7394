// What `simplify` ships: a light reference (a few hundred triangles) ships the triangle route,
// the reference whole, scored as that baseline is, with no cage fitted.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "fit/result_folder.h"
#include "mesh/mesh_geometry.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "simplify/simplify_job.h"
#include "small_simplify.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

namespace fs = std::filesystem;

TEST(SimplifyRoute, ALightReferenceShipsTheTriangleRouteWhole) {
    const auto dir = scratchDir("simplify_route_light");
    const mesh::PolygonMesh light = mesh::makeLumpySphere(3, 0.15f, 4);
    mesh::writeObj(dir / "light.obj", light);
    const auto report = simplify::toJson(simplify::runSimplify(smallSimplify(dir / "light.obj", dir / "out", 20)));

    // No --budget: the reference compressed (under the smallest default budget) is the budget,
    // and the triangle route holds all of it.
    EXPECT_TRUE(report["simplify"]["budget_derived"].get<bool>());
    const auto& route = report["route"];
    const std::string shipped = route["shipped"].get<std::string>();
    ASSERT_TRUE(shipped == "decimation" || shipped == "gltfpack") << route.dump();
    EXPECT_NE(route["why"].get<std::string>().find("whole"), std::string::npos) << route.dump();
    EXPECT_EQ(route["path"], "asset.glb");
    const auto& baseline = report["baselines"][shipped];
    EXPECT_EQ(baseline["triangles"].get<int>(), mesh::triangulated(light).faceCount());
    EXPECT_LT(baseline["triangles"].get<int>(), 2000);  // a light reference
    // What ships is the baseline: its file, its bytes, its scores; no cage was fitted.
    EXPECT_EQ(fs::file_size(dir / "out" / "asset.glb"), report["bytes"].get<std::uintmax_t>());
    EXPECT_EQ(report["bytes"], baseline["bytes"]);
    EXPECT_LE(report["bytes"].get<std::uintmax_t>(), report["simplify"]["budget"].get<std::uintmax_t>());
    EXPECT_EQ(report["psnr_holdout"], baseline["psnr_holdout"]);
    EXPECT_EQ(report["margin_db"][shipped].get<double>(), 0.0);
    EXPECT_FALSE(report.contains("steps"));
    EXPECT_FALSE(fs::exists(dir / "out" / "asset.subd"));
    EXPECT_TRUE(report["seconds_by_stage"].contains("triangle_route"));
    EXPECT_FALSE(report["seconds_by_stage"].contains("fit"));
    // A viewer opens what shipped.
    const fit::ResultFolder folder = fit::readResultFolder(dir / "out");
    ASSERT_FALSE(folder.entries.empty());
    EXPECT_EQ(folder.entries.front().levels.front(), dir / "out" / "asset.glb");
}

}  // namespace
}  // namespace subdfit::test
