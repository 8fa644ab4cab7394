// Reading back what a fit or simplify folder shipped (fit/result_folder.h): subdfit's asset and
// scores, the reference, the baselines that are there in the comparison's order; a folder that
// holds no result is refused naming it. A result folder is input like any other: a baseline path
// that leads outside it (absolute, climbing, through a symlink) or to something that is not a
// regular file is left out with a note, and the reference is opened only when it is still the
// file the result was made from.
#include <gtest/gtest.h>

#include <limits>
#include <sys/stat.h>

#include <cmath>
#include <fstream>

#include "error_message.h"
#include "fit/fit_report.h"
#include "fit/result_folder.h"
#include "io/output_folder.h"
#include "test_paths.h"

namespace subdfit::fit {
namespace {

void writeFile(const std::filesystem::path& path, const std::string& text) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path) << text;
}

std::filesystem::path resolvedPath(const std::filesystem::path& path) {
    return std::filesystem::weakly_canonical(path);
}

nlohmann::json simplifyReport(const std::filesystem::path& reference) {
    return {{"bytes", 18415},
            {"psnr_holdout", 30.1},
            {"ssim_holdout", 0.88},
            {"settings", {{"shading", "auto"}}},
            {"reference", referenceJson(reference, 12)},
            {"comparison_columns", {"reference", "subdfit", "decimation", "gltfpack", "bake"}},
            {"baselines",
             {{"bake", {{"bytes", 17710}, {"psnr_holdout", 29.4}, {"path", "baselines/bake/asset.subd"}}},
              {"decimation",
               {{"bytes", 18404}, {"psnr_holdout", 23.5}, {"ssim_holdout", 0.35}, {"path", "baselines/decimated.glb"}}},
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
    EXPECT_EQ(folder.entries[0].levels, std::vector<std::filesystem::path>{resolvedPath(dir / "asset.subd")});
    EXPECT_EQ(folder.entries[0].bytes, 18415u);
    EXPECT_DOUBLE_EQ(folder.entries[0].psnrHoldout, 30.1);
    EXPECT_EQ(folder.entries[1].name, "decimation");
    EXPECT_EQ(folder.entries[1].levels,
              std::vector<std::filesystem::path>{resolvedPath(dir / "baselines/decimated.glb")});
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
                                                  {"reference", referenceJson(dir / "gone.obj", 0)}}
                                       .dump());
    const ResultFolder folder = readResultFolder(dir);
    ASSERT_EQ(folder.entries.size(), 1u);
    EXPECT_EQ(folder.entries[0].bytes, 1234u);
    EXPECT_TRUE(std::isnan(folder.entries[0].ssimHoldout));
    EXPECT_TRUE(folder.reference.empty());
    ASSERT_EQ(folder.notes.size(), 1u);
    EXPECT_NE(folder.notes[0].find("gone.obj"), std::string::npos);
}

// A report's byte counts are read as far as a count holds them: one past 2^64 is the most, a
// negative one none (the fuzzer's case: a conversion out of range is undefined).
TEST(ResultFolder, ByteCountsOutOfRangeAreClampedNotConverted) {
    const auto dir = test::scratchDir("result_folder_huge");
    writeFile(dir / "asset.subd", "SUBD");
    for (const auto& [stated, read] :
         {std::pair{1.8e28, std::numeric_limits<std::uintmax_t>::max()}, std::pair{-5.0, std::uintmax_t(0)}}) {
        writeFile(
            dir / "report.json",
            nlohmann::json{{"psnr_holdout", 25.0}, {"bytes", stated}, {"reference", referenceJson(dir / "gone.obj", 0)}}
                .dump());
        const ResultFolder folder = readResultFolder(dir);
        ASSERT_EQ(folder.entries.size(), 1u);
        EXPECT_EQ(folder.entries[0].bytes, read) << stated;
    }
}

TEST(ResultFolder, AFolderWithoutAResultIsRefusedNamingIt) {
    const auto dir = test::scratchDir("result_folder_none");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir / "missing"); }).find("missing: not a folder"),
              std::string::npos);
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("not a subdfit result: no report.json"),
              std::string::npos);
    writeFile(dir / "report.json", "{");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("no asset.subd"), std::string::npos);
    writeFile(dir / "asset.subd", "SUBD");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("report.json: not JSON"), std::string::npos);
}

TEST(ResultFolder, BaselinesNamedOutsideTheFolderAreLeftOutWithANote) {
    namespace fs = std::filesystem;
    const auto root = test::scratchDir("result_folder_hostile");
    const auto dir = root / "result";
    writeFile(root / "outside/secret.obj", "v 0 0 0\n");
    writeFile(dir / "asset.subd", "SUBD");
    fs::create_directories(dir / "baselines");
    fs::create_symlink(root / "outside/secret.obj", dir / "baselines/link.obj");
    fs::create_directory_symlink(root / "outside", dir / "baselines/d");
    ASSERT_EQ(mkfifo((dir / "baselines/fifo.glb").c_str(), 0600), 0);
    fs::create_directory(dir / "baselines/folder.glb");
    nlohmann::json baselines = nlohmann::json::object();
    const std::vector<std::string> paths = {(root / "outside/secret.obj").string(),
                                            "../outside/secret.obj",
                                            "baselines/link.obj",
                                            "baselines/d/secret.obj",
                                            "baselines/fifo.glb",
                                            "baselines/folder.glb",
                                            "baselines/../../outside/secret.obj",
                                            "",
                                            "\x1b]0;owned\x07x.glb"};
    for (size_t k = 0; k < paths.size(); ++k)
        baselines[std::string(1, char('a' + k))] = {{"path", paths[k]}, {"bytes", 10}};
    writeFile(dir / "report.json", nlohmann::json{{"baselines", baselines}, {"settings", "not an object"}}.dump());

    const ResultFolder folder = readResultFolder(dir);
    ASSERT_EQ(folder.entries.size(), 1u);  // subdfit's asset alone
    for (const auto& entry : folder.entries)
        for (const auto& level : entry.levels) EXPECT_TRUE(io::isStrictlyInside(level, resolvedPath(dir))) << level;
    size_t leftOut = 0;
    for (const std::string& note : folder.notes) {
        EXPECT_EQ(note.find('\x1b'), std::string::npos) << note;  // nothing from the report reaches a terminal raw
        leftOut += note.find("not shown") != std::string::npos;
    }
    EXPECT_EQ(leftOut, paths.size());
    EXPECT_TRUE(folder.settings.is_object());
}

TEST(ResultFolder, WhatShippedMustBeARegularFileInsideTheFolder) {
    namespace fs = std::filesystem;
    const auto root = test::scratchDir("result_folder_route");
    const auto dir = root / "result";
    writeFile(root / "outside.glb", "glTF");
    writeFile(dir / "asset.glb", "glTF");
    fs::create_symlink(root / "outside.glb", dir / "link.glb");
    for (const std::string& path :
         {(root / "outside.glb").string(), std::string("../outside.glb"), std::string("link.glb")}) {
        writeFile(dir / "report.json", nlohmann::json{{"route", {{"path", path}}}}.dump());
        EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("report.json: what shipped"),
                  std::string::npos)
            << path;
    }
    // report.json itself may not lead elsewhere.
    writeFile(root / "elsewhere.json", "{}");
    fs::remove(dir / "report.json");
    fs::create_symlink(root / "elsewhere.json", dir / "report.json");
    EXPECT_NE(test::errorMessage([&] { readResultFolder(dir); }).find("report.json: not a regular file inside"),
              std::string::npos);
}

TEST(ResultFolder, TheReferenceIsOpenedOnlyWhenItIsTheFileTheResultWasMadeFrom) {
    const auto dir = test::scratchDir("result_folder_reference");
    writeFile(dir / "reference.obj", "v 0 0 0\n");
    writeFile(dir / "other.obj", "v 1 1 1\n");
    writeFile(dir / "result/asset.subd", "SUBD");
    nlohmann::json reference = referenceJson(dir / "reference.obj", 1);
    ASSERT_TRUE(reference.contains("xxh3_128"));

    writeFile(dir / "result/report.json", nlohmann::json{{"reference", reference}}.dump());
    EXPECT_EQ(readResultFolder(dir / "result").reference, dir / "reference.obj");

    // Another file at the path, a path to any other file, no digest, a FIFO: not opened, said why.
    writeFile(dir / "reference.obj", "v 0 0 1\n");
    EXPECT_TRUE(readResultFolder(dir / "result").reference.empty());
    reference["path"] = (dir / "other.obj").string();
    writeFile(dir / "result/report.json", nlohmann::json{{"reference", reference}}.dump());
    const ResultFolder other = readResultFolder(dir / "result");
    EXPECT_TRUE(other.reference.empty());
    ASSERT_FALSE(other.notes.empty());
    EXPECT_NE(other.notes[0].find("not the file the result was made from"), std::string::npos);
    writeFile(dir / "result/report.json", nlohmann::json{{"reference", {{"path", "/etc/passwd"}}}}.dump());
    const ResultFolder noDigest = readResultFolder(dir / "result");
    EXPECT_TRUE(noDigest.reference.empty());
    EXPECT_NE(noDigest.notes[0].find("records no digest"), std::string::npos);
    ASSERT_EQ(mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
    reference["path"] = (dir / "fifo.obj").string();
    writeFile(dir / "result/report.json", nlohmann::json{{"reference", reference}}.dump());
    EXPECT_TRUE(readResultFolder(dir / "result").reference.empty());
}

}  // namespace
}  // namespace subdfit::fit
