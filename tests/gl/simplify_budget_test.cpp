// `simplify --budget`: what ships fits the bytes, the report says what was tried, and a budget
// nothing fits is refused before anything is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <tuple>

#include "error_message.h"
#include "codec/subd_format.h"
#include "fit/fit_scene.h"
#include "gl_test_context.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "simplify/budget_search.h"
#include "simplify/compare/textured_baselines.h"
#include "simplify/simplify_job.h"
#include "simplify/triangle_route.h"
#include "small_simplify.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::test {
namespace {

namespace fs = std::filesystem;

std::string readBytes(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Whether every position lies on a grid of 2^bits − 1 steps over the positions' bounding cube
// (asset.subd's quantisation of a cage, codec/cage_coding.h).
bool onPositionGrid(const std::vector<glm::vec3>& positions, int bits) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}), levels = float((1 << bits) - 1);
    for (const glm::vec3& p : positions)
        for (int a = 0; a < 3; ++a) {
            const float t = (p[a] - lo[a]) / extent * levels;
            if (std::abs(t - std::round(t)) > 0.01f) return false;
        }
    return true;
}

simplify::SimplifyOptions budgeted(const fs::path& reference, const fs::path& out, std::uintmax_t budget) {
    simplify::SimplifyOptions o = smallSimplify(reference, out, 20);
    o.fit.checkpointEvery = 10;
    o.budget = budget;
    return o;
}

TEST(SimplifyBudget, ShipsWithinTheBudgetAndListsTheCandidates) {
    const auto dir = scratchDir("simplify_budget");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(5, 0.15f, 3, 40, 0.005f, 0.02f));
    constexpr std::uintmax_t kBudget = 3000;
    const auto report = simplify::toJson(simplify::runSimplify(budgeted(dir / "lumpy.obj", dir / "out", kBudget)));

    EXPECT_LE(fs::file_size(dir / "out" / "asset.subd"), kBudget);
    EXPECT_EQ(report["bytes"].get<std::uintmax_t>(), fs::file_size(dir / "out" / "asset.subd"));
    const auto& budget = report["budget"];
    EXPECT_EQ(budget["bytes"].get<std::uintmax_t>(), kBudget);
    EXPECT_FALSE(budget["over_budget"].get<bool>());
    // Several cages were tried, some over the budget. Where several lie within 20 % of the
    // lowest monitor loss, those were scored on the training views too, and only they; the chosen
    // one is, of them, the smallest whose settled loss is within 2 % of the lowest and that saves
    // at least five times the loss it gives up in bytes (both relative to the lowest). A lone
    // leader is chosen as it is.
    ASSERT_GE(budget["candidates"].size(), 3u);
    bool someOver = false;
    double lowestMonitored = 1e30;
    for (const auto& c : budget["candidates"]) {
        if (c["bytes"].get<std::uintmax_t>() > kBudget) someOver = true;
        else lowestMonitored = std::min(lowestMonitored, c["monitor_loss"].get<double>());
    }
    EXPECT_TRUE(someOver);
    // The same for the candidates with maps, among themselves: the bake route's choice.
    double lowestWithMaps = 1e30;
    for (const auto& c : budget["candidates"])
        if (c["bytes"].get<std::uintmax_t>() <= kBudget && c["maps"] != "none")
            lowestWithMaps = std::min(lowestWithMaps, c["monitor_loss"].get<double>());
    int nearCount = 0, nearWithMaps = 0;
    for (const auto& c : budget["candidates"]) {
        if (c["bytes"].get<std::uintmax_t>() > kBudget) continue;
        nearCount += c["monitor_loss"].get<double>() <= 1.2 * lowestMonitored;
        nearWithMaps += c["maps"] != "none" && c["monitor_loss"].get<double>() <= 1.2 * lowestWithMaps;
    }
    double bestLoss = 1e30, bestBytes = 0.0;
    for (const auto& c : budget["candidates"]) {
        if (c["bytes"].get<std::uintmax_t>() > kBudget) continue;
        const bool near = c["monitor_loss"].get<double>() <= 1.2 * lowestMonitored;
        const bool nearAmongMaps = c["maps"] != "none" && c["monitor_loss"].get<double>() <= 1.2 * lowestWithMaps;
        EXPECT_EQ(c.contains("settled_loss"), (near && nearCount > 1) || (nearAmongMaps && nearWithMaps > 1))
            << c.dump();
        if (near && c.contains("settled_loss") && c["settled_loss"].get<double>() < bestLoss) {
            bestLoss = c["settled_loss"].get<double>();
            bestBytes = double(c["bytes"].get<std::uintmax_t>());
        }
    }
    // A rung of maps over the budget at 14-bit positions, its resolution's first on its cage, is
    // judged again at 10 bits next (the cage is most of its bytes).
    const auto& tried = budget["candidates"];
    int retried = 0;
    for (size_t k = 0; k + 1 < tried.size(); ++k) {
        const auto& c = tried[k];
        if (c["maps"] == "none" || c["position_bits"] != 14 || c["bytes"].get<std::uintmax_t>() <= kBudget) continue;
        const auto sameRung = [&](const nlohmann::json& o) {
            return o["faces"] == c["faces"] && o["maps"] == c["maps"] && o["map_resolution"] == c["map_resolution"];
        };
        // On a cage of the ladder (judged bare first; a grown cage is not), its resolution's first fit.
        bool ladderCage = false, firstOfItsResolution = true;
        for (size_t j = 0; j < k; ++j) {
            ladderCage |= tried[j]["faces"] == c["faces"] && tried[j]["maps"] == "none";
            firstOfItsResolution &= !(sameRung(tried[j]) && tried[j]["bytes"].get<std::uintmax_t>() <= kBudget);
        }
        if (!ladderCage || !firstOfItsResolution) continue;
        const auto& next = tried[k + 1];
        EXPECT_TRUE(sameRung(next) && next["map_bits"] == c["map_bits"] && next["position_bits"] == 10)
            << c.dump() << " then " << next.dump();
        ++retried;
    }
    EXPECT_GT(retried, 0) << "no rung over the budget at 14 bits: the case is not exercised";
    auto worthIt = [&](const nlohmann::json& c) {
        if (!c.contains("settled_loss")) return false;
        const double lossGivenUp = c["settled_loss"].get<double>() / bestLoss - 1.0;
        return lossGivenUp <= 0.02 && 1.0 - double(c["bytes"].get<std::uintmax_t>()) / bestBytes >= 5.0 * lossGivenUp;
    };
    const auto chosenBytes = budget["chosen"]["bytes"].get<std::uintmax_t>();
    if (nearCount > 1) {
        EXPECT_TRUE(worthIt(budget["chosen"]));
        for (const auto& c : budget["candidates"])
            if (c["bytes"].get<std::uintmax_t>() < chosenBytes) {
                EXPECT_FALSE(worthIt(c)) << c.dump();
            }
    } else {
        EXPECT_EQ(budget["chosen"]["monitor_loss"].get<double>(), lowestMonitored);
    }
    // The best candidate was tried again with its cage's positions at fewer bits: fewer bytes
    // than its 14-bit twin (a cage grown with the bytes saved has none). The chosen bits are what
    // the fit ships, on the grid they say.
    int twins = 0;
    for (const auto& c : budget["candidates"]) {
        if (c["position_bits"].get<int>() == 14) continue;
        const auto twin = std::find_if(budget["candidates"].begin(), budget["candidates"].end(), [&](const auto& t) {
            return t["position_bits"] == 14 && t["faces"] == c["faces"] && t["maps"] == c["maps"] &&
                   t["map_resolution"] == c["map_resolution"] && t["map_bits"] == c["map_bits"];
        });
        if (twin == budget["candidates"].end()) continue;
        ++twins;
        EXPECT_LT(c["bytes"].get<std::uintmax_t>(), (*twin)["bytes"].get<std::uintmax_t>()) << c.dump();
    }
    EXPECT_GE(twins, 1);
    EXPECT_EQ(report["settings"]["position_bits"], budget["chosen"]["position_bits"]);
    const int bits = budget["chosen"]["position_bits"].get<int>();
    const auto cageShipped = codec::readSubd(dir / "out" / "asset.subd").cage;
    EXPECT_TRUE(onPositionGrid(cageShipped.positions, bits)) << bits;
    EXPECT_FALSE(onPositionGrid(cageShipped.positions, bits - 2)) << bits;
    // What was chosen is what was fitted.
    EXPECT_EQ(report["cage"]["faces"], budget["chosen"]["faces"]);
    EXPECT_EQ(report["settings"]["maps"], budget["chosen"]["maps"]);
    // Every candidate with heights that was judged says what shades them, and the fitted one
    // ships that.
    for (const auto& c : budget["candidates"])
        EXPECT_EQ(c.contains("shading_normal"),
                  c.contains("monitor_loss") && c["maps"].get<std::string>().find("displacement") != std::string::npos)
            << c.dump();
    if (budget["chosen"].contains("shading_normal")) {
        EXPECT_EQ(report["settings"]["shading_normal"], budget["chosen"]["shading_normal"]);
        const auto shipped = codec::readSubd(dir / "out" / "asset.subd");
        EXPECT_EQ(nameOf(shipped.maps.shadingNormal), budget["chosen"]["shading_normal"].get<std::string>());
    }
    // The triangle baselines are held to the budget; a dense reference at a budget this tight
    // ships its cage, which leads them on the held-out views.
    EXPECT_LE(report["baselines"]["decimation"]["bytes"].get<std::uintmax_t>(), kBudget);
    EXPECT_EQ(report["route"]["shipped"], "cage") << report["route"].dump();
    for (const char* baseline : {"decimation", "gltfpack"})
        if (report["baselines"][baseline].contains("psnr_holdout")) {
            EXPECT_GE(report["margin_db"][baseline].get<double>(), 0.0) << baseline;
        }
    // The bake route says whether it fits too (it is the best candidate with maps when one fits).
    const auto& bake = report["baselines"]["bake"];
    EXPECT_EQ(bake["over_budget"].get<bool>(), bake["bytes"].get<std::uintmax_t>() > kBudget);

    // --compare none ships the same asset, and writes no baselines, no comparison, no distances.
    auto production = budgeted(dir / "lumpy.obj", dir / "none", kBudget);
    production.compare = simplify::CompareLevel::None;
    const auto none = simplify::toJson(simplify::runSimplify(production));
    EXPECT_EQ(none["route"]["shipped"], "cage");
    EXPECT_EQ(readBytes(dir / "none" / "asset.subd"), readBytes(dir / "out" / "asset.subd"));
    EXPECT_FALSE(fs::exists(dir / "none" / "baselines"));
    EXPECT_FALSE(fs::exists(dir / "none" / "comparison.png"));
    EXPECT_FALSE(none.contains("baselines"));
    for (const char* distance : {"chamfer", "hausdorff", "mean_distance"})  // said, not a 0 that reads as perfect
        EXPECT_EQ(none[distance], "not measured") << distance;
    EXPECT_TRUE(none["route"]["weighed"].contains("decimation"));
    EXPECT_FALSE(none["seconds_by_stage"].contains("baseline_bake"));
    EXPECT_TRUE(fs::exists(dir / "out" / "comparison.png"));
}

// --prefix: the file grows past the asset the prefix's budget ships, and its first bytes decode
// to that asset (what --budget PREFIX alone ships), cage and heights, exactly.
TEST(SimplifyPrefix, TheFileGrowsAndItsFirstBytesAreWhatThePrefixsBudgetShips) {
    const auto dir = scratchDir("simplify_prefix");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(5, 0.15f, 3, 40, 0.005f, 0.02f));
    constexpr std::uintmax_t kPrefix = 3000, kBudget = 8000;
    auto grown = budgeted(dir / "lumpy.obj", dir / "grown", kBudget);
    grown.prefix = kPrefix;
    grown.compare = simplify::CompareLevel::None;
    const auto report = simplify::toJson(simplify::runSimplify(grown));
    const auto& prefix = report["prefix"];
    ASSERT_TRUE(prefix.contains("grown")) << prefix.dump();
    const std::uintmax_t bytes = fs::file_size(dir / "grown" / "asset.subd");
    EXPECT_EQ(report["bytes"].get<std::uintmax_t>(), bytes);
    EXPECT_LE(bytes, kBudget);
    EXPECT_GT(bytes, kPrefix);
    EXPECT_LT(prefix["grown"]["choosing_loss"].get<double>(), prefix["asset_choosing_loss"].get<double>());
    EXPECT_TRUE(fs::exists(dir / "grown" / "asset.usdz"));

    auto alone = budgeted(dir / "lumpy.obj", dir / "alone", kPrefix);
    alone.compare = simplify::CompareLevel::None;
    simplify::runSimplify(alone);
    EXPECT_EQ(prefix["bytes"].get<std::uintmax_t>(), fs::file_size(dir / "alone" / "asset.subd"));
    const codec::SubdAsset asset = codec::readSubd(dir / "alone" / "asset.subd");
    const codec::SubdAsset first =
        codec::readSubd(dir / "grown" / "asset.subd", nullptr, {}, prefix["bytes"].get<std::size_t>());
    EXPECT_EQ(first.cage.positions, asset.cage.positions);
    ASSERT_FALSE(asset.maps.displacement.empty());
    EXPECT_EQ(first.maps.displacement, asset.maps.displacement);
}

// A scene for the search alone: few views, small, a placeholder cage (the search brings its own).
fit::FitScene smallSearchScene(const mesh::PolygonMesh& reference, const std::string& name) {
    fit::FitOptions o;
    o.out = scratchDir(name);
    o.steps = 20;
    o.views = 4;
    o.holdoutViews = 2;
    o.resolution = 64;
    return fit::FitScene(fit::resolved(o), programs(), mesh::makeQuadSphere(2), reference);
}

// simplify chooses on the monitor's cameras drawn as a viewer shows them, as the held-out views
// judge what ships; the fit's own schedule reads them single-sample, as it fits.
TEST(SimplifyBudget, ChoicesSeeTheMonitorCamerasAsAViewerDoes) {
    const fit::FitScene scene =
        smallSearchScene(mesh::makeLumpySphere(5, 0.15f, 5, 40, 0.005f, 0.02f), "simplify_choosing");
    const auto& choosing = scene.choosing(programs());
    EXPECT_EQ(scene.monitor.supersampling(), 1);
    EXPECT_EQ(choosing.supersampling(), fit::kViewerSupersampling);
    EXPECT_EQ(scene.holdout.supersampling(), fit::kViewerSupersampling);
    ASSERT_EQ(choosing.size(), scene.monitor.size());
    int outline = 0;  // pixels whose anti-aliased target differs from the single sample
    for (int v = 0; v < scene.monitor.size(); ++v) {
        EXPECT_EQ(choosing.camera(v).eye, scene.monitor.camera(v).eye);
        const auto single = scene.monitor.readColor(v), seen = choosing.readColor(v);
        ASSERT_EQ(single.size(), seen.size());
        for (size_t p = 0; p < single.size(); ++p) outline += glm::length(single[p] - seen[p]) > 0.05f;
    }
    EXPECT_GT(outline, 0);
    expectNoGlError();
}

// The lumpy sphere searched at 3 KB on a small scene: the case the search's tests vary one
// setting of.
struct LumpySearch {
    explicit LumpySearch(const std::string& name) : scene(smallSearchScene(reference, name)) {
        search.budget = 3000;
        search.faceCounts = simplify::faceCountsFor(search.budget, reference.faceCount(), 16000);
    }
    simplify::BudgetChoice run(simplify::CageShape shape = simplify::CageShape::Triangles) {
        simplify::CageLadder cages(reference, search.faceCounts, shape);
        return simplify::searchBudget(programs(), scene, reference, search, cages, {});
    }

    const mesh::PolygonMesh reference = mesh::makeLumpySphere(5, 0.15f, 5, 40, 0.005f, 0.02f);
    fit::FitScene scene;
    simplify::BudgetSearch search;
};

// Where the search's cage ladder ends in `tried`: at the first candidate of the phases after it,
// which code the best at 12 or 11 position bits or judge a cage the ladder did not (judged bare first).
size_t ladderEnd(const std::vector<simplify::BudgetCandidate>& tried) {
    for (size_t k = 0; k < tried.size(); ++k) {
        const bool cageOfTheLadder = std::any_of(tried.begin(), tried.begin() + std::ptrdiff_t(k), [&](const auto& c) {
            return c.faces == tried[k].faces && !c.maps.any() && c.positionBits == 14;
        });
        const bool ladderBits = tried[k].positionBits == 14 || tried[k].positionBits == 10;
        if (!ladderBits || (tried[k].maps.any() && !cageOfTheLadder)) return k;
    }
    return tried.size();
}

// On one cage, a map resolution whose lowest loss trails a coarser one's by over 2 % with over
// 90 % of the budget spent ends that cage's ladder of those maps: no finer resolution is tried there.
TEST(SimplifyBudget, AMapResolutionTrailingACoarserOneNearTheBudgetEndsItsLadderOnThatCage) {
    LumpySearch lumpy("simplify_budget_map_ladder_end");
    lumpy.search.budget = 2500;
    lumpy.search.faceCounts = simplify::faceCountsFor(lumpy.search.budget, lumpy.reference.faceCount(), 16000);
    const simplify::BudgetChoice choice = lumpy.run();
    const auto& tried = choice.tried;
    const size_t end = ladderEnd(tried);
    int ended = 0;
    for (size_t k = 0; k < end; ++k) {
        if (tried[k].maps.any()) continue;  // a cage's bare candidate: its ladders follow
        // By maps: each resolution's lowest loss within the budget, and the finest tried.
        std::map<std::string, std::map<int, std::pair<double, std::uintmax_t>>> lowest;  // and its bytes
        std::map<std::string, int> finest;
        for (size_t j = k + 1; j < end && tried[j].faces == tried[k].faces && tried[j].maps.any(); ++j) {
            const auto& c = tried[j];
            const std::string kind = maps::toString(c.maps);
            finest[kind] = std::max(finest[kind], c.mapResolution);
            if (c.bytes > lumpy.search.budget) continue;
            auto& own = lowest[kind].try_emplace(c.mapResolution, INFINITY, 0).first->second;
            if (c.monitorLoss < own.first) own = {c.monitorLoss, c.bytes};
        }
        for (const auto& [kind, byResolution] : lowest) {
            double coarser = INFINITY;
            for (const auto& [resolution, lowestAt] : byResolution) {
                const auto [loss, bytes] = lowestAt;
                if (loss > 1.02 * coarser && double(bytes) > 0.9 * double(lumpy.search.budget)) {
                    ++ended;
                    EXPECT_EQ(finest[kind], resolution) << tried[k].faces << " faces: maps finer than T=" << resolution
                                                        << ", which trails near the budget, were tried";
                    break;
                }
                coarser = std::min(coarser, loss);
            }
        }
    }
    EXPECT_GT(ended, 0) << "no resolution trailed a coarser one: the case is not exercised";
    expectNoGlError();
}

// Where the best candidate has maps, the best bare cage is coded at fewer position bits, grown
// to the budget and tried as quads only where, grown, it may reach the best (bareMayReach).
TEST(SimplifyBudget, ABareCageThatCannotReachTheBestIsNotGrown) {
    int grown = 0, notGrown = 0;
    for (const std::uintmax_t budget : {std::uintmax_t(3000), std::uintmax_t(12000)}) {
        LumpySearch lumpy("simplify_budget_bare_growth");
        lumpy.search.budget = budget;
        // A short ladder of heights alone: the three largest cages, T = 2 at 4 bits.
        lumpy.search.faceCounts = simplify::faceCountsFor(budget, lumpy.reference.faceCount(), 16000);
        lumpy.search.faceCounts.resize(std::min<size_t>(lumpy.search.faceCounts.size(), 3));
        lumpy.search.allowedMaps = {maps::MapKind::Displacement};
        lumpy.search.mapResolutions = {2};
        lumpy.search.mapBits = {4};
        lumpy.search.quadTrial = true;
        const simplify::BudgetChoice choice = lumpy.run(simplify::CageShape::Auto);
        const auto& tried = choice.tried;
        const size_t end = ladderEnd(tried);
        const simplify::BudgetCandidate *best = nullptr, *bestBare = nullptr;
        for (size_t k = 0; k < end; ++k) {
            const auto& c = tried[k];
            if (c.bytes > budget) continue;
            if (!best || c.monitorLoss < best->monitorLoss) best = &c;
            if (!c.maps.any() && (!bestBare || c.monitorLoss < bestBare->monitorLoss)) bestBare = &c;
        }
        ASSERT_TRUE(best && bestBare);
        ASSERT_TRUE(best->maps.any()) << budget << " bytes: the best is bare; the case is not exercised";
        // The search weighs the preferred candidate, within 2 % of the lowest: clear of the line here.
        const bool reaches = bareMayReach(*bestBare, best->monitorLoss, budget);
        ASSERT_EQ(reaches, bareMayReach(*bestBare, 1.02 * best->monitorLoss, budget))
            << budget << " bytes: too near to call";
        const bool bareGrown =
            std::any_of(tried.begin() + std::ptrdiff_t(end), tried.end(), [](const auto& c) { return !c.maps.any(); });
        const bool quadTried = std::any_of(tried.begin(), tried.end(), [](const auto& c) { return c.quads > 0; });
        EXPECT_EQ(bareGrown, reaches) << budget << " bytes";
        EXPECT_EQ(quadTried, reaches) << budget << " bytes";
        ++(reaches ? grown : notGrown);
    }
    EXPECT_EQ(grown, 1) << "at 12 000 bytes the bare cage grown may reach the best";
    EXPECT_EQ(notGrown, 1) << "at 3 000 bytes it may not";
    expectNoGlError();
}

// Where even the best candidate trails the triangle route by more than a fit gains, no cage is
// fitted, so which of the near ties would be chosen changes nothing: the same search then draws
// no training view to settle them, and chooses the lowest monitor loss.
TEST(SimplifyBudget, NoNearTieIsSettledWhereNoCandidateWillBeFitted) {
    LumpySearch lumpy("simplify_budget_unsettled");
    // At 2.5 KB its candidates tie (at 3 KB one with heights at 10-bit positions leads alone).
    lumpy.search.budget = 2500;
    lumpy.search.faceCounts = simplify::faceCountsFor(lumpy.search.budget, lumpy.reference.faceCount(), 16000);
    auto searched = [&](double leastFitted) {
        lumpy.search.leastFittedMonitorPsnr = leastFitted;
        return lumpy.run();
    };
    const simplify::BudgetChoice settled = searched(-INFINITY), unsettled = searched(INFINITY);

    const auto settledCount = [](const simplify::BudgetChoice& c) {
        return std::count_if(c.tried.begin(), c.tried.end(), [](const auto& t) { return t.settledLoss > 0.0; });
    };
    ASSERT_GT(settledCount(settled), 1) << "no near ties to settle: the case no longer tests this";
    EXPECT_EQ(settledCount(unsettled), 0);
    ASSERT_EQ(unsettled.tried.size(), settled.tried.size());
    double lowest = INFINITY;
    for (size_t k = 0; k < settled.tried.size(); ++k) {
        EXPECT_EQ(unsettled.tried[k].monitorLoss, settled.tried[k].monitorLoss);
        if (settled.tried[k].monitorLoss > 0.0) lowest = std::min(lowest, settled.tried[k].monitorLoss);
    }
    EXPECT_EQ(unsettled.chosen.monitorLoss, lowest);
    expectNoGlError();
}

// --cage-shape auto: the triangle ladder's best bare cage is tried once more as a quad-dominant
// remesh at its bytes and precision, judged like any candidate; without the trial, no quad cage.
TEST(SimplifyBudget, TheQuadTrialRemeshesTheBestBareCageAtItsBytes) {
    LumpySearch lumpy("simplify_budget_quad_trial");
    const simplify::BudgetSearch& search = lumpy.search;
    lumpy.search.allowedMaps = {};
    auto searched = [&](bool trial) {
        lumpy.search.quadTrial = trial;
        return lumpy.run(simplify::CageShape::Auto);
    };
    const simplify::BudgetChoice without = searched(false), with = searched(true);
    EXPECT_TRUE(std::none_of(without.tried.begin(), without.tried.end(), [](const auto& c) { return c.quads > 0; }));
    ASSERT_GT(with.tried.size(), without.tried.size());
    const simplify::BudgetCandidate* bestTriangles = nullptr;  // the best bare triangle cage within the budget
    for (const auto& c : without.tried)
        if (c.monitorLoss > 0.0 && (!bestTriangles || c.monitorLoss < bestTriangles->monitorLoss)) bestTriangles = &c;
    ASSERT_NE(bestTriangles, nullptr);
    // The trial's cages: the first from half the triangles' faces, then grown while bytes are left
    // (or shrunk until one fits), as the triangle cage was.
    std::vector<const simplify::BudgetCandidate*> fitting;
    for (size_t k = without.tried.size(); k < with.tried.size(); ++k) {
        const simplify::BudgetCandidate& c = with.tried[k];
        EXPECT_TRUE(c.quadDominant()) << c.faces << " faces, " << c.quads << " quads";
        EXPECT_EQ(c.positionBits, bestTriangles->positionBits);
        EXPECT_FALSE(c.maps.any());
        if (c.bytes <= search.budget) {
            EXPECT_GT(c.monitorLoss, 0.0);
            if (!fitting.empty()) {
                EXPECT_GT(c.faces, fitting.back()->faces);
            }
            fitting.push_back(&c);
        }
    }
    ASSERT_FALSE(fitting.empty()) << "no quad cage within the budget";
    EXPECT_NEAR(double(with.tried[without.tried.size()].faces), 0.5 * bestTriangles->faces,
                0.25 * bestTriangles->faces);
    // Judged as the others are: a quad cage ships where it is one of the trial's and the lowest
    // after settling; a clear lead on the monitor views decides either way.
    const auto isTrial = [&](const simplify::BudgetCandidate& c) {
        return std::any_of(fitting.begin(), fitting.end(),
                           [&](const auto* f) { return f->faces == c.faces && f->bytes == c.bytes; });
    };
    EXPECT_EQ(with.chosen.quadDominant(), isTrial(with.chosen));
    const auto lowestQuad = *std::min_element(
        fitting.begin(), fitting.end(), [](const auto* a, const auto* b) { return a->monitorLoss < b->monitorLoss; });
    const double monitorGap = lowestQuad->monitorLoss / bestTriangles->monitorLoss;
    if (monitorGap < 0.8) {
        EXPECT_TRUE(with.chosen.quadDominant());
    }
    if (monitorGap > 1.25) {
        EXPECT_FALSE(with.chosen.quadDominant());
    }
    expectNoGlError();
}

// At a tight budget the first vertex coding (14-bit positions and normals) can fit at no texture
// scale, a decimation being held above its fewest triangles by its texture seams: the scales are
// then weighed at the leanest coding, and the baseline still ships within the budget.
TEST(TexturedBaselines, ATightBudgetStillShipsADecimationWithinIt) {
    const mesh::PolygonMesh duck = mesh::triangulated(mesh::loadReference(assetPath("gltf/Duck/Duck.glb")));
    fit::FitScene scene = smallSearchScene(duck, "textured_baseline_tight");
    constexpr std::uintmax_t kBudget = 5000;
    const simplify::Quality q = simplify::texturedDecimationBaseline(
        programs(), scene, kBudget, {.dir = scratchDir("textured_baseline_tight_out"), .distance = false});
    ASSERT_GT(q.details["encodings_tried"].at(0)["bytes"].get<std::uintmax_t>(), kBudget)
        << "the first coding fits: the case no longer tests this";
    EXPECT_LE(q.bytes, kBudget) << q.details.dump();
    EXPECT_FALSE(q.details["over_budget"].get<bool>());
    expectNoGlError();
}

// Each comparison level makes its list of triangle baselines (decimation first, as the route
// weighs it; clustering only with `all`), each within the budget, its file as it reports.
TEST(TriangleBaselines, EachLevelMakesItsListWithinTheBudget) {
    const fit::FitScene scene =
        smallSearchScene(mesh::makeLumpySphere(5, 0.15f, 5, 40, 0.005f, 0.02f), "triangle_baselines");
    constexpr std::uintmax_t kBudget = 3000;
    const std::vector<std::pair<simplify::CompareLevel, std::vector<std::string>>> levels{
        {simplify::CompareLevel::None, {"decimation"}},
        {simplify::CompareLevel::Fast, {"decimation", "gltfpack"}},
        {simplify::CompareLevel::All, {"decimation", "gltfpack", "clustering"}}};
    for (const auto& [level, expected] : levels) {
        SCOPED_TRACE(nameOf(level));
        const simplify::BaselineSettings settings{.dir = scratchDir("triangle_baselines_" + std::string(nameOf(level))),
                                                  .distance = false};
        const simplify::TriangleBaselines made =
            simplify::triangleBaselines(programs(), scene, kBudget, settings, level);
        std::vector<std::string> names;
        for (const auto& b : made.made) names.push_back(b.name);
        for (const auto& [name, why] : made.unavailable) names.push_back(name);  // gltfpack, where not on PATH
        std::sort(names.begin() + 1, names.end());
        std::vector<std::string> sorted = expected;
        std::sort(sorted.begin() + 1, sorted.end());
        EXPECT_EQ(names, sorted);
        ASSERT_EQ(made.made.front().name, "decimation");
        for (const auto& b : made.made) {
            SCOPED_TRACE(b.name);
            EXPECT_LE(b.quality.bytes, kBudget);
            EXPECT_GT(b.quality.psnrHoldout, 10.0);
            EXPECT_EQ(fs::file_size(settings.dir.parent_path() / b.quality.shipped), b.quality.bytes);
        }
    }
    expectNoGlError();
}

// The bare cages' bytes with each appearance tile resolution, cage by cage (faces -> T -> bytes).
std::map<int, std::map<int, std::uintmax_t>> appearanceBytes(std::uintmax_t budget) {
    const mesh::PolygonMesh duck = mesh::triangulated(mesh::loadReference(assetPath("gltf/Duck/Duck.glb")));
    fit::FitScene scene = smallSearchScene(duck, "simplify_budget_appearances");
    simplify::BudgetSearch search;
    search.budget = budget;
    search.faceCounts = {800, 400};
    search.allowedMaps = {};
    search.appearance = {maps::MapKind::BaseColor};
    search.appearanceResolutions = {2, 4, 8, 16};
    simplify::CageLadder cages(duck, search.faceCounts);
    const simplify::BudgetChoice choice = simplify::searchBudget(programs(), scene, duck, search, cages, {});
    std::map<int, std::map<int, std::uintmax_t>> bytes;
    for (const auto& c : choice.tried) bytes[c.faces][c.appearanceResolution] = c.bytes;
    return bytes;
}

// The search bakes no finer appearance that two coarser ones predict over the budget: each
// doubling of the texels adds more bytes than the last, so the last bytes plus the last increase
// are the least the next can cost.
TEST(SimplifyBudget, AFinerAppearanceTwoCoarserOnesPredictOverIsNotBaked) {
    // The premise, where every resolution is judged: the increases grow.
    const auto all = appearanceBytes(1u << 30);
    for (const auto& [faces, byT] : all) {
        ASSERT_EQ(byT.size(), 4u) << faces << " faces";
        for (int t : {8, 16})
            EXPECT_GE(byT.at(t) - byT.at(t / 2), byT.at(t / 2) - byT.at(t / 4)) << faces << " faces, T=" << t;
    }
    // A budget between a finer resolution's prediction and its bytes: predicted over, not baked.
    const auto& [faces, byT] = *all.begin();
    const std::uintmax_t predicted16 = 2 * byT.at(8) - byT.at(4);
    ASSERT_LT(byT.at(8), predicted16);
    const auto some = appearanceBytes((byT.at(8) + predicted16) / 2);
    ASSERT_TRUE(some.at(faces).count(8)) << "T=8 fits and is judged";
    EXPECT_FALSE(some.at(faces).count(16)) << "T=16 was baked though predicted over";
    expectNoGlError();
}

// A light faceted reference (flat triangles, shaded with smooth vertex normals): heights baked
// onto a cage of its own density copy its facets, and shading them with the limit normal is what
// looks like it. The search judges both and says which won.
TEST(SimplifyBudget, HeightsOnAFacetedReferenceShadeWithTheLimitNormal) {
    const auto dir = scratchDir("simplify_budget_faceted");
    const mesh::PolygonMesh faceted = mesh::triangulated(mesh::makeQuadSphere(4));  // 192 flat triangles
    mesh::writeObj(dir / "faceted.obj", faceted);
    auto o = budgeted(dir / "faceted.obj", dir / "out", 4000);
    o.fit.resolution = 128;
    o.fit.maps = {maps::MapKind::Displacement};
    o.route =
        simplify::RouteChoice::Cage;  // it ships whole as triangles otherwise: this is about the cage the search finds
    const auto report = simplify::toJson(simplify::runSimplify(o));
    int ownDensity = 0;
    for (const auto& c : report["budget"]["candidates"]) {
        if (c["faces"].get<int>() != faceted.faceCount() || !c.contains("shading_normal") ||
            !c.contains("monitor_loss"))
            continue;
        ++ownDensity;
        EXPECT_EQ(c["shading_normal"], "limit") << c.dump();
    }
    EXPECT_GT(ownDensity, 0) << report["budget"].dump();
}

// catmark_cubes_infsharp at 700 bytes: the search's bake fits, the fit wins on the choosing
// views, and its rougher heights code to over 700 bytes at the fewest bits the search judged: the
// most of the way to it from its bake that fits (bisected) is weighed against the bake as both
// are coded, the better ships within the budget, and the report says why.
TEST(SimplifyBudget, AFitCodedOverTheBudgetShipsTheMostOfItThatFitsOrItsBake) {
    const auto dir = scratchDir("simplify_budget_fit_over");
    simplify::SimplifyOptions o = smallSimplify(assetPath("osd-shapes/catmark_cubes_infsharp.obj"), dir / "out", 60);
    o.budget = 700;
    o.compare = simplify::CompareLevel::None;
    const auto report = simplify::toJson(simplify::runSimplify(o));

    const auto& verdict = report["fit_verdict"];
    EXPECT_NE(verdict.value("why", "").find("over the budget"), std::string::npos) << verdict.dump();
    EXPECT_GT(verdict["over_budget_bytes"].get<std::uintmax_t>(), *o.budget) << verdict.dump();
    EXPECT_LE(report["bytes"].get<std::uintmax_t>(), *o.budget);
    EXPECT_FALSE(report["budget"]["over_budget"].get<bool>());
    ASSERT_TRUE(verdict.contains("within_budget_fraction")) << "no way from the bake fits: the case is not exercised";
    const double fraction = verdict["within_budget_fraction"];
    EXPECT_GT(fraction, 0.0);
    EXPECT_LT(fraction, 1.0);
    const double fit = verdict["shipped_choosing_loss"]["fit"], bake = verdict["shipped_choosing_loss"]["bake"];
    EXPECT_EQ(verdict["shipped"], fit < bake ? "fit" : "bake") << verdict.dump();
    // A bake that ships is the candidate the search judged (at 10-bit positions), to the byte.
    if (verdict["shipped"] == "bake") {
        EXPECT_EQ(report["bytes"], report["budget"]["chosen"]["bytes"]);
    }
    if (report["route"]["shipped"] == "cage") {
        EXPECT_EQ(fs::file_size(dir / "out" / "asset.subd"), report["bytes"].get<std::uintmax_t>());
    }
}

// The fit and its bake weighed again as they ship (asset.subd decoded): catmark_flap at 500
// bytes, the fit leads before coding and trails once its heights are coded at 4 bits, so the
// bake ships; catmark_chaikin2 at 900 bytes, it leads both ways and ships.
TEST(SimplifyBudget, TheFitShipsOnlyWhereItLeadsItsBakeAsCoded) {
    const auto dir = scratchDir("simplify_budget_as_coded");
    for (const auto& [shape, budget, ships] :
         {std::tuple{"catmark_flap", 500u, "bake"}, std::tuple{"catmark_chaikin2", 900u, "fit"}}) {
        const fs::path out = dir / shape;
        simplify::SimplifyOptions o = smallSimplify(assetPath(std::string("osd-shapes/") + shape + ".obj"), out, 60);
        o.budget = budget;
        o.compare = simplify::CompareLevel::None;
        const auto report = simplify::toJson(simplify::runSimplify(o));
        const auto& verdict = report["fit_verdict"];
        ASSERT_TRUE(verdict.contains("shipped_choosing_loss")) << shape << verdict.dump();
        EXPECT_LT(verdict["choosing_loss"]["fit"].get<double>(), verdict["choosing_loss"]["bake"].get<double>());
        const double fit = verdict["shipped_choosing_loss"]["fit"], bake = verdict["shipped_choosing_loss"]["bake"];
        EXPECT_EQ(verdict["shipped"], fit < bake ? "fit" : "bake") << verdict.dump();
        EXPECT_EQ(verdict["shipped"], ships) << shape << verdict.dump();
        EXPECT_EQ(fs::file_size(out / "asset.subd"), report["bytes"].get<std::uintmax_t>());
        EXPECT_LE(report["bytes"].get<std::uintmax_t>(), budget);
    }
}

// --coded-steps: the heights fitted as coded after the fit (fit/coded_refinement.h) replace what
// shipped only within the budget and closer on the choosing views, and the report says so.
TEST(SimplifyBudget, HeightsFittedAsCodedShipOnlyWithinTheBudgetAndCloser) {
    const auto dir = scratchDir("simplify_budget_coded_fit");
    simplify::SimplifyOptions o = smallSimplify(assetPath("osd-shapes/catmark_flap.obj"), dir / "out", 60);
    o.budget = 500;
    o.compare = simplify::CompareLevel::None;
    o.route = simplify::RouteChoice::Cage;
    o.codedSteps = 100;
    const auto report = simplify::toJson(simplify::runSimplify(o));
    ASSERT_TRUE(report.contains("coded_fit")) << report.dump();
    const auto& coded = report["coded_fit"];
    EXPECT_GT(coded["steps"].get<int>(), 0);
    EXPECT_EQ(coded["bits"], report["budget"]["map_bits"]);
    EXPECT_LE(coded["best_loss"].get<double>(), coded["start_loss"].get<double>());
    if (coded["ships"].get<bool>()) {
        EXPECT_LT(coded["refined_choosing_loss"].get<double>(), coded["shipped_choosing_loss"].get<double>());
        EXPECT_EQ(coded["bytes"], report["bytes"]);
    }
    EXPECT_EQ(fs::file_size(dir / "out" / "asset.subd"), report["bytes"].get<std::uintmax_t>());
    EXPECT_LE(report["bytes"].get<std::uintmax_t>(), *o.budget);
}

TEST(SimplifyBudget, ABudgetNoCageFitsIsRefusedNamingTheReference) {
    const auto dir = scratchDir("simplify_budget_tiny");
    mesh::writeObj(dir / "lumpy.obj", mesh::makeLumpySphere(4, 0.15f, 3));
    const std::string message =
        errorMessage([&] { simplify::runSimplify(budgeted(dir / "lumpy.obj", dir / "out", 120)); });
    EXPECT_NE(message.find("lumpy.obj"), std::string::npos) << message;
    EXPECT_NE(message.find("--budget"), std::string::npos) << message;
    EXPECT_FALSE(fs::exists(dir / "out" / "asset.subd"));
    EXPECT_FALSE(fs::exists(dir / "out" / "report.json"));
}

}  // namespace
}  // namespace subdfit::test
