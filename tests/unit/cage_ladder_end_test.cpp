// ladderPastItsBest: the budget search stops climbing down its cage ladder once two cages in a
// row trail the best (which has maps) by kTrailingLoss, and not before.
#include <gtest/gtest.h>

#include <vector>

#include "simplify/budget_search.h"

namespace subdfit::simplify {
namespace {

TEST(CageLadderEnd, TwoCagesTrailingABestWithMapsEndIt) {
    // The README demo's ladder at 20 KB: its best at 3 124 faces, then 1.59x and 1.80x.
    const std::vector<double> demo{0.001306, 0.002693, 0.0005888, 0.000935};
    EXPECT_FALSE(ladderPastItsBest(true, demo)) << "one cage trails";
    EXPECT_TRUE(ladderPastItsBest(true, {0.001306, 0.002693, 0.0005888, 0.000935, 0.001061}));
}

TEST(CageLadderEnd, ABareBestNeverEndsIt) {
    // Where maps fit only on small cages, the larger bare ones trail on the way to them.
    EXPECT_FALSE(ladderPastItsBest(false, {0.001, 0.002, 0.003, 0.004}));
}

TEST(CageLadderEnd, ACageNearTheBestStartsTheCountAgain) {
    // The relief Spot at 10 KB: 606 faces within 1.5x of 973's, and 379 faces then lead.
    EXPECT_FALSE(ladderPastItsBest(true, {0.004012, 0.008143, 0.001881, 0.001585, 0.001672}));
    EXPECT_FALSE(ladderPastItsBest(true, {0.001, 0.0016, 0.0012, 0.0016}));
    EXPECT_TRUE(ladderPastItsBest(true, {0.001, 0.0016, 0.0012, 0.0016, 0.0017}));
    EXPECT_FALSE(ladderPastItsBest(true, {}));
}

}  // namespace
}  // namespace subdfit::simplify
