// What `simplify` ships and at what budget: the route rule (the cage only where it wins on the
// held-out views), the default budget, and the search for the most triangles a file holds.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <vector>

#include "simplify/compare/triangle_encoding.h"
#include "simplify/route.h"
#include "util/error.h"

namespace subdfit::test {
namespace {

using simplify::Quality;

Quality scored(double psnr, std::uintmax_t bytes, bool overBudget = false) {
    Quality q;
    q.psnrHoldout = psnr;
    q.bytes = bytes;
    q.details = {{"over_budget", overBudget}};
    return q;
}

// The triangle baselines as made, named as the route names them.
std::vector<simplify::MadeBaseline> made(std::optional<Quality> decimation, std::optional<Quality> gltfpack = {}) {
    std::vector<simplify::MadeBaseline> m;
    if (decimation) m.push_back({"decimation", "decimation + Draco", *decimation});
    if (gltfpack) m.push_back({"gltfpack", "gltfpack", *gltfpack});
    return m;
}

TEST(SimplifyRoute, TheCageShipsOnlyWhereItWinsOnTheHeldOutViews) {
    const auto baselines = made(scored(31.0, 19000), scored(30.0, 18000));
    const auto best = simplify::bestTriangleRoute(baselines);
    EXPECT_EQ(best.name, "decimation");
    const auto lost = simplify::chooseRoute(scored(30.5, 18500), best);
    EXPECT_EQ(lost.shipped, "decimation");
    EXPECT_EQ(lost.path, "asset.glb");
    EXPECT_NE(lost.why.find("0.50 dB"), std::string::npos) << lost.why;
    const auto won = simplify::chooseRoute(scored(31.5, 18500), best);
    EXPECT_EQ(won.shipped, "cage");
    EXPECT_EQ(won.path, "asset.subd");
}

TEST(SimplifyRoute, ATriangleRouteOverTheBudgetIsNeverShipped) {
    const Quality over = scored(50.0, 30000, /*overBudget=*/true), within = scored(20.0, 19000);
    EXPECT_EQ(simplify::bestTriangleRoute(made(over, within)).name, "gltfpack");
    const auto overAlone = made(over);
    EXPECT_EQ(simplify::bestTriangleRoute(overAlone).quality, nullptr);
    EXPECT_EQ(simplify::chooseRoute(scored(10.0, 100), simplify::bestTriangleRoute(overAlone)).shipped, "cage");
}

TEST(SimplifyRoute, ACageOverTheBudgetShipsOnlyWhereNoTriangleRouteFits) {
    const auto baselines = made(scored(20.0, 900));
    const auto best = simplify::bestTriangleRoute(baselines);
    const auto over = simplify::chooseRoute(scored(30.0, 1219), best, 940);
    EXPECT_EQ(over.shipped, "decimation");
    EXPECT_NE(over.why.find("1219 bytes, over the budget"), std::string::npos) << over.why;
    EXPECT_EQ(simplify::chooseRoute(scored(30.0, 940), best, 940).shipped, "cage");
    EXPECT_EQ(simplify::chooseRoute(scored(30.0, 1219), best).shipped, "cage");  // no budget set
    EXPECT_EQ(simplify::chooseRoute(scored(30.0, 1219), simplify::bestTriangleRoute({}), 940).shipped, "cage");
}

TEST(SimplifyRoute, BeforeTheFitTrianglesShipWhenTheyHoldEveryTriangleOrLeadFar) {
    Quality decimation = scored(40.0, 5000);
    decimation.details["monitor_psnr"] = 40.0;
    const auto baselines = made(decimation);
    const auto best = simplify::bestTriangleRoute(baselines);
    using simplify::Holds;
    const auto whole = simplify::routeBeforeFit(best, Holds::Whole, std::nullopt);
    ASSERT_TRUE(whole);
    EXPECT_NE(whole->why.find("whole"), std::string::npos) << whole->why;
    const auto everyTriangle = simplify::routeBeforeFit(best, Holds::EveryTriangle, std::nullopt);
    ASSERT_TRUE(everyTriangle);
    EXPECT_NE(everyTriangle->why.find("every triangle"), std::string::npos) << everyTriangle->why;
    EXPECT_FALSE(simplify::routeBeforeFit(best, Holds::Part, std::nullopt));
    EXPECT_FALSE(simplify::routeBeforeFit(best, Holds::Part, 40.0 - simplify::kMostFitGainDb + 0.1));
    EXPECT_TRUE(simplify::routeBeforeFit(best, Holds::Part, 40.0 - simplify::kMostFitGainDb - 0.1));
}

TEST(SimplifyRoute, TheDefaultBudgetIsATenthOfTheReferenceCompressedNeverMoreThanIt) {
    EXPECT_EQ(simplify::defaultBudget(5000), 5000u);  // light: its whole self
    EXPECT_EQ(simplify::defaultBudget(100000), simplify::kSmallestDefaultBudget);
    EXPECT_EQ(simplify::defaultBudget(3000000), 300000u);
}

TEST(SimplifyRoute, CompareLevelsParseAndRefuse) {
    EXPECT_EQ(parseNamed<simplify::CompareLevel>("none"), simplify::CompareLevel::None);
    EXPECT_EQ(parseNamed<simplify::CompareLevel>("fast"), simplify::CompareLevel::Fast);
    EXPECT_EQ(parseNamed<simplify::CompareLevel>("full"), simplify::CompareLevel::Full);
    EXPECT_EQ(parseNamed<simplify::CompareLevel>("all"), simplify::CompareLevel::All);
    EXPECT_EQ(parseNamed<simplify::CompareLevel>("most"), std::nullopt);
    EXPECT_EQ(nameOf(simplify::CompareLevel::Fast), "fast");
}

// bytes(t) = header + rate · t, probed as a shipping function would be.
struct LinearFile {
    double header, rate;
    int probes = 0;
    std::uintmax_t operator()(int triangles) {
        ++probes;
        return std::uintmax_t(std::lround(header + rate * triangles));
    }
};

TEST(MostWithinBudget, FindsTheMostTrianglesToAFewPerThousandInAFewProbes) {
    for (const double rate : {1.3, 2.7, 9.0}) {
        LinearFile file{900.0, rate};
        const std::uintmax_t budget = 20000;
        const int most = 210000;
        const int exact = int(std::floor((double(budget) - file.header) / rate));
        const int found = simplify::mostWithinBudget(12, most, budget, std::ref(file));
        EXPECT_LE(found, exact) << rate;
        EXPECT_GE(found, exact - exact / 200 - 1) << rate;
        EXPECT_LE(file.probes, 10) << rate;  // bisection over 210 000 counts takes 18
    }
}

TEST(MostWithinBudget, ReachesAllTrianglesAndStopsAtTheFewest) {
    LinearFile small{100.0, 2.0};
    EXPECT_EQ(simplify::mostWithinBudget(12, 500, 5000, std::ref(small)), 500);
    LinearFile heavy{6000.0, 2.0};
    std::uintmax_t last = 0;
    EXPECT_EQ(simplify::mostWithinBudget(12, 500, 5000, [&](int t) { return last = heavy(t); }), 12);
    EXPECT_GT(last, 5000u);  // left as shipped, over: the report says so
}

TEST(MostWithinBudget, LeavesTheFileAsShippedAtTheCountReturned) {
    // A stair: bytes jump in steps of 64 triangles, as a coder's blocks might.
    int lastShipped = -1;
    const auto stair = [&](int t) {
        lastShipped = t;
        return std::uintmax_t(500 + 3 * 64 * (t / 64));
    };
    const int found = simplify::mostWithinBudget(12, 100000, 30000, stair, 7000);
    EXPECT_EQ(lastShipped, found);
    EXPECT_LE(stair(found), 30000u);
}

}  // namespace
}  // namespace subdfit::test
