// Reading back what a fit or simplify folder shipped (fit/result_folder.h): subdfit's asset and
// scores, the reference, the baselines that are there in the comparison's order; a folder that
// holds no result is refused naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "error_message.h"
#include "fit/result_folder.h"
#include "test_paths.h"

namespace subdfit::fit {
namespace {

void writeFile(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

nlohmann::json simplifyReport(const std::filesystem::path& reference) {
    return {{"bytes", 18415},
            {"psnr_holdout", 30.1},
            {"ssim_holdout", 0.88},
            {"settings", {{"shading", "auto"}}},
            {"reference", {{"path", reference.string()}, {"triangles", 12}}},
            {"comparison_columns", {"reference", "subdfit", "decimation", "gltfpack", "bake"}},
            {"baselines",
             {{"bake", {{"bytes", 17710}, {"psnr_holdout", 29.4}, {"path", "baselines/bake/asset.subd"}}},
              {"decimation", {{"bytes", 18404}, {"psnr_holdout", 23.5}, {"ssim_holdout", 0.35}, {"path", "baselines/decimated.glb"}}},
              {"gltfpack", {{"skipped", "gltfpack is not on PATH"}}}}}};
}

TEST(ResultFolder, ReadsTheAssetTheReferenceAndTheBaselinesThatAreThere) {
    const auto dir = test::scratchDir("result_folder");
    writeFile(dir / "reference.obj", "v 0 0 0\n");
    writeFile(dir / "asset.subd", "SUBD");
    writeFile(dir / "baselines/decimated.glb", "glTF");
    writeFile(dir / "report.json", simplifyReport(dir / "reference.obj").dump());

    const ResultFolder folder = readResultFolder(dir);
    EXPECT_EQ(folder.reference, dir / "reference.obj");
    ASSERT_EQ(folder.entries.size(), 2u);  // the bake's file is missing, gltfpack was skipped
    EXPECT_EQ(folder.entries[0].name, "subdfit");
    EXPECT_EQ(folder.entries[0].levels, std::vector<std::filesystem::path>{dir / "asset.subd"});
    EXPECT_EQ(folder.entries[0].bytes, 18415u);
    EXPECT_DOUBLE_EQ(folder.entries[0].psnrHoldout, 30.1);
    EXPECT_EQ(folder.entries[1].name, "decimation");
    EXPECT_EQ(folder.entries[1].levels, std::vector<std::filesystem::path>{dir / "baselines/decimated.glb"});
    EXPECT_DOUBLE_EQ(folder.entries[1].ssimHoldout, 0.35);
    ASSERT_EQ(folder.notes.size(), 2u);
    EXPECT_NE(folder.notes[0].find("gltfpack"), std::string::npos);
    EXPECT_NE(folder.notes[1].find("bake"), std::string::npos);

    // Once there, the bake comes last, as in the comparison.
    writeFile(dir / "baselines/bake/asset.subd", "SUBD");
    const ResultFolder again = readResultFolder(dir);
    ASSERT_EQ(again.entries.size(), 3u);
    EXPECT_EQ(again.entries[2].name, "bake");
}

TEST(ResultFolder, AFitFolderHasNoBaselinesAndItsBytesFromTheExports) {
    const auto dir = test::scratchDir("result_folder_fit");
    writeFile(dir / "asset.subd", "SUBD");
    writeFile(dir / "report.json", nlohmann::json{{"psnr_holdout", 25.0},
                                                  {"exports", {{"asset.subd", 1234}, {"cage.obj", 99}}},
                                                  {"reference", {{"path", (dir / "gone.obj").string()}}}}
                                       .dump());
    const ResultFolder folder = readResultFolder(dir);
    ASSERT_EQ(folder.entries.size(), 1u);
    EXPECT_EQ(folder.entries[0].bytes, 1234u);
    EXPECT_TRUE(std::isnan(folder.entries[0].ssimHoldout));
    EXPECT_TRUE(folder.reference.empty());
    ASSERT_EQ(folder.notes.size(), 1u);
    EXPECT_NE(folder.notes[0].find("gone.obj"), std::string::npos);
}

TEST(ResultFolder, AFolderWithoutAResultIsRefusedNamingIt) {
    const auto dir = test::scratchDir("result_folder_none");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir / "missing"); }).find("missing: not a folder"), std::string::npos);
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("not a subdfit result: no report.json"), std::string::npos);
    writeFile(dir / "report.json", "{");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("no asset.subd"), std::string::npos);
    writeFile(dir / "asset.subd", "SUBD");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("report.json: not JSON"), std::string::npos);
}

}  // namespace
}  // namespace subdfit::fit
