// `simplify` end to end on a small generated asset: the report's numbers agree with the files
// on disk and compare at equal bytes; and `batch` skips, resumes, shards and records failures.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <iterator>

#include <glm/geometric.hpp>

#include "codec/subd_format.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "simplify/batch.h"
#include "simplify/simplify_job.h"
#include "util/interrupt.h"
#include "scene_fixture.h"
#include "small_simplify.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

namespace fs = std::filesystem;

// 120 faces with heights and normals at T = 2 (both, so that both are checked), a preview.
simplify::SimplifyOptions smallMappedSimplify(const fs::path& reference, const fs::path& out) {
    simplify::SimplifyOptions o = smallSimplify(reference, out, 30);
    o.fit.maps = {maps::MapKind::Displacement, maps::MapKind::NormalMap};
    o.fit.mapResolution = 2;
    o.fit.checkpointEvery = 5;
    o.fit.preview = true;
    o.faces = 120;
    return o;
}

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

nlohmann::json readJson(const fs::path& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
}

TEST(SimplifyJob, ReportMatchesTheFilesAndComparesAtEqualBytes) {
    const auto dir = scratchDir("simplify_job");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(4, 0.15f, 4));
    auto options = smallMappedSimplify(dir / "lumpy.obj", dir / "out");
    options.route =
        simplify::RouteChoice::Cage;  // what a fitted cage ships, whether or not the triangle route scores better
    const auto report = simplify::toJson(simplify::runSimplify(options));
    EXPECT_EQ(report["route"]["shipped"], "cage");

    // bytes: exactly what the shipped files weigh on disk.
    std::uintmax_t onDisk = 0;
    for (const auto& [name, bytes] : report["files"].items()) {
        ASSERT_TRUE(fs::exists(dir / "out" / name)) << name;
        EXPECT_EQ(fs::file_size(dir / "out" / name), bytes.get<std::uintmax_t>()) << name;
        onDisk += fs::file_size(dir / "out" / name);
    }
    // One file ships: asset.subd. The USD package, the atlases and fitted.glb are conveniences,
    // each named in `exports` with its bytes; no bare cage.glb that looks complete and is not.
    EXPECT_EQ(report["files"].size(), 1u);
    EXPECT_TRUE(report["files"].contains("asset.subd"));
    for (const char* convenience : {"asset.usdz", "normal.png", "fitted.glb"}) {
        EXPECT_FALSE(report["files"].contains(convenience)) << convenience;
        ASSERT_TRUE(fs::exists(dir / "out" / convenience)) << convenience;
        EXPECT_EQ(report["exports"][convenience].get<std::uintmax_t>(), fs::file_size(dir / "out" / convenience))
            << convenience;
    }
    EXPECT_FALSE(fs::exists(dir / "out" / "cage.glb"));
    EXPECT_EQ(report["bytes"].get<std::uintmax_t>(), onDisk);

    const auto& decimation = report["baselines"]["decimation"];
    const auto& bake = report["baselines"]["bake"];
    EXPECT_LE(decimation["bytes"].get<std::uintmax_t>(),
              onDisk);                                   // --faces alone: the route is weighed at the cage's bytes
    EXPECT_GT(decimation["triangles"].get<int>(), 120);  // the maps' bytes buy it more triangles
    EXPECT_EQ(fs::file_size(dir / "out" / "baselines" / "decimated.glb"), decimation["bytes"].get<std::uintmax_t>());
    // The bake ships the same cage and map formats: within a few percent of subdfit's bytes.
    EXPECT_NEAR(double(bake["bytes"].get<std::uintmax_t>()), double(onDisk), 0.1 * double(onDisk));

    for (const auto* q : {&report, &decimation, &bake}) {
        EXPECT_TRUE(std::isfinite((*q)["psnr_holdout"].get<double>()));
        EXPECT_GT((*q)["psnr_holdout"].get<double>(), 15.0);
        EXPECT_GT((*q)["ssim_holdout"].get<double>(), 0.0);
        EXPECT_LT((*q)["ssim_holdout"].get<double>(), 1.0);  // no method renders the reference exactly
        EXPECT_GE((*q)["chamfer"].get<double>(), 0.0);
        // One PSNR per held-out view, whose mean loss is the one reported.
        const auto& views = (*q)["psnr_holdout_views"];
        ASSERT_EQ(views.size(), 2u);
        double meanMse = 0.0;
        for (const auto& p : views) meanMse += std::pow(10.0, -p.get<double>() / 10.0) / double(views.size());
        EXPECT_NEAR(-10.0 * std::log10(meanMse), (*q)["psnr_holdout"].get<double>(), 1e-3);
        EXPECT_GE((*q)["hausdorff"].get<double>(), std::sqrt((*q)["chamfer"].get<double>() / 2.0) * 0.5);
    }
    EXPECT_NEAR(report["margin_db"]["bake"].get<double>(),
                report["psnr_holdout"].get<double>() - bake["psnr_holdout"].get<double>(), 1e-9);
    EXPECT_GT(report["psnr_holdout"].get<double>(), report["psnr_holdout_initial"].get<double>());
    // What the coding cost: the shipped state unquantised, at the default 12 bits a height within
    // half a dB of its file.
    ASSERT_TRUE(report.contains("psnr_holdout_unquantised"));
    EXPECT_NEAR(report["psnr_holdout_unquantised"].get<double>(), report["psnr_holdout"].get<double>(), 0.5);
    EXPECT_TRUE(report["finite"].get<bool>());
    EXPECT_GT(fs::file_size(dir / "out" / "comparison.png"), 1000u);
}

// Resumed past the step where the maps were baked, the run must keep what that step set up (a
// frozen cage, slow map rates) and end where an uninterrupted run does.
TEST(SimplifyJob, ResumedAfterTheBakeEndsWhereAStraightRunDoes) {
    const auto dir = scratchDir("simplify_resume");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(4, 0.15f, 4));
    auto options = smallMappedSimplify(dir / "lumpy.obj", dir / "straight");
    options.fit.steps = 20;
    options.fit.mapsStart = 0.5f;  // bake at step 10
    const auto straight = *simplify::runSimplify(options).fit;

    options.fit.out = dir / "resumed";
    std::atomic<bool> cancel{false};
    // Interrupted, simplify keeps its checkpoint and writes no results.
    EXPECT_THROW(
        simplify::runSimplify(
            options, {.progress = [&](const fit::Progress& p) { cancel = cancel || p.step >= 14; }, .cancel = &cancel}),
        Interrupted);
    EXPECT_TRUE(fs::exists(dir / "resumed" / "checkpoint.bin"));
    EXPECT_FALSE(fs::exists(dir / "resumed" / "report.json"));
    EXPECT_FALSE(fs::exists(dir / "resumed" / "initial_cage.obj"));
    options.fit.resume = true;
    const auto resumed = *simplify::runSimplify(options).fit;
    EXPECT_EQ(resumed.resumedFromStep, 14);

    const auto a = mesh::loadMesh(dir / "straight" / "cage.obj").positions;
    const auto b = mesh::loadMesh(dir / "resumed" / "cage.obj").positions;
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(a, b) << "largest vertex difference " << maxDistance(a, b);
    EXPECT_EQ(resumed.holdoutAfter.psnr, straight.holdoutAfter.psnr);
    for (const char* map : {"displacement.exr", "normal.png"})
        EXPECT_EQ(readBytes(dir / "straight" / map), readBytes(dir / "resumed" / map)) << map;
}

// Maps baked before the first step are the fit's start: a run of no steps ships the bake, and
// its report scores the start as what shipped (not the cage before its maps).
TEST(SimplifyJob, MapsBakedAtTheStartAreTheStartItReports) {
    const auto dir = scratchDir("simplify_start_is_bake");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(4, 0.15f, 4));
    auto options = smallMappedSimplify(dir / "lumpy.obj", dir / "out");
    options.fit.steps = 0;
    options.fit.mapsStart = 0.0f;
    const fit::FitReport report = *simplify::runSimplify(options).fit;
    EXPECT_EQ(report.steps, 0);
    EXPECT_EQ(report.holdoutBefore.psnr, report.holdoutAfter.psnr);
    EXPECT_EQ(report.holdoutBefore.ssim, report.holdoutAfter.ssim);
}

// Same inputs, same seed, same machine: the same bytes (docs/architecture.md, Determinism). G
// sums in fixed point and every CPU stage is ordered, so nothing varies but the run time.
TEST(SimplifyJob, TwoRunsOfOneSeedWriteTheSameFiles) {
    const auto dir = scratchDir("simplify_repeat");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(4, 0.15f, 4));
    const auto first = simplify::toJson(simplify::runSimplify(smallMappedSimplify(dir / "lumpy.obj", dir / "first")));
    const auto second = simplify::toJson(simplify::runSimplify(smallMappedSimplify(dir / "lumpy.obj", dir / "second")));
    for (const auto& [name, bytes] : first["files"].items())
        EXPECT_EQ(readBytes(dir / "first" / name), readBytes(dir / "second" / name)) << name;
    for (const char* name : {"cage.obj", "fitted.glb", "initial_cage.obj"})
        EXPECT_EQ(readBytes(dir / "first" / name), readBytes(dir / "second" / name)) << name;
    for (const char* key : {"psnr_holdout", "psnr_holdout_initial", "chamfer"})
        EXPECT_EQ(first[key], second[key]) << key;
}

// --cage-shape paired: the cage that ships, in cage.obj and in asset.subd, is the decimated
// triangles joined in pairs: quad-dominant, about the faces asked, the same faces in both files.
TEST(SimplifyJob, APairedCageShipsQuadDominant) {
    const auto dir = scratchDir("simplify_paired");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(4, 0.15f, 4));
    simplify::SimplifyOptions options = smallMappedSimplify(dir / "lumpy.obj", dir / "out");
    options.fit.steps = 5;
    options.cageShape = simplify::CageShape::Paired;
    options.route = simplify::RouteChoice::Cage;
    options.compare = simplify::CompareLevel::None;
    simplify::runSimplify(options);
    const mesh::PolygonMesh cage = mesh::loadMesh(dir / "out" / "cage.obj");
    const int quads = mesh::quadCount(cage);
    EXPECT_GE(double(quads), 0.9 * cage.faceCount()) << quads << " quads of " << cage.faceCount();
    EXPECT_GE(cage.faceCount(), 120);
    EXPECT_LT(cage.faceCount(), 150);
    std::vector<int> shipped = codec::readSubd(dir / "out" / "asset.subd").cage.faceSizes, written = cage.faceSizes;
    std::sort(shipped.begin(), shipped.end());  // the coded cage numbers its faces its own way
    std::sort(written.begin(), written.end());
    EXPECT_EQ(shipped, written);
}

TEST(SimplifyBatch, SkipsFinishedResumesInterruptedAndRecordsFailures) {
    const auto dir = scratchDir("simplify_batch");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(3, 0.15f, 4));
    mesh::writeObj(dir / "ball.obj", mesh::makeQuadSphere(5));
    std::vector<simplify::BatchItem> items;
    for (const char* name : {"lumpy", "missing", "ball"}) {
        auto o = smallMappedSimplify(dir / (std::string(name) + ".obj"), {});
        o.fit.steps = 20;
        o.fit.maps = {};
        items.push_back({name, o});
    }
    const fs::path out = dir / "out";

    // Interrupted after 5 steps of the first asset (inside its fit's probation, which may end it
    // at step 10): it stays .partial, with its checkpoint.
    std::atomic<bool> cancel{false};
    const fit::FitHooks stopEarly{.progress = [&](const fit::Progress& p) { cancel = cancel || p.step >= 5; },
                                  .cancel = &cancel};
    const auto first = simplify::runBatch(items, out, {}, stopEarly);
    EXPECT_TRUE(first.interrupted);
    EXPECT_EQ(first.finished, 0);
    EXPECT_EQ(readJson(out / "lumpy.partial" / "status.json")["state"], "interrupted");
    EXPECT_TRUE(fs::exists(out / "lumpy.partial" / "checkpoint.bin"));
    EXPECT_FALSE(fs::exists(out / "lumpy"));

    // Shard 1/2 runs only asset 1 (the missing file): recorded as failed, named in the status.
    const auto shard = simplify::runBatch(items, out, {1, 2});
    EXPECT_EQ(shard.otherShards, 2);
    EXPECT_EQ(shard.failed, 1);
    const auto failed = readJson(out / "missing.partial" / "status.json");
    EXPECT_EQ(failed["state"], "failed");
    EXPECT_NE(failed["error"].get<std::string>().find("missing.obj"), std::string::npos);

    // A plain re-run resumes the interrupted asset, finishes the others, still fails the bad one,
    // whose retry finds its partial folder from the same input and settings (nothing changed).
    std::string said;
    const auto second = simplify::runBatch(items, out, {}, {}, [&](const std::string& line) { said += line + "\n"; });
    EXPECT_EQ(said.find("another version"), std::string::npos) << said;
    EXPECT_EQ(second.finished, 2);
    // Each finished asset counts the route it shipped, and its status says which.
    int routed = 0;
    for (const auto& [route, count] : second.routes) routed += count;
    EXPECT_EQ(routed, 2);
    EXPECT_EQ(second.routes.count(readJson(out / "ball" / "status.json")["route"].get<std::string>()), 1u);
    EXPECT_EQ(second.failed, 1);
    EXPECT_FALSE(fs::exists(out / "lumpy.partial"));
    EXPECT_EQ(readJson(out / "lumpy" / "status.json")["state"], "done");
    const auto resumed = readJson(out / "lumpy" / "report.json");
    EXPECT_EQ(resumed["resumed_from_step"], 5);
    // To the end of its 20 steps, or of its probation when that found no gain.
    EXPECT_TRUE(resumed["steps"] == 20 || (resumed["stop_reason"] == "no_gain" && resumed["steps"] == 10))
        << resumed["steps"];
    EXPECT_EQ(readJson(out / "ball" / "report.json")["resumed_from_step"], 0);

    // And once more: nothing left to do but the failure.
    const auto third = simplify::runBatch(items, out, {});
    EXPECT_EQ(third.skipped, 2);
    EXPECT_EQ(third.routes, second.routes);  // skipped as done, counted from their status
    EXPECT_EQ(third.finished, 0);
    EXPECT_EQ(third.failed, 1);
}

}  // namespace
}  // namespace subdfit::test
