// bareMayReach: the budget search grows its best bare cage to the budget (and remeshes it into
// quads) only where, grown, it may reach the best candidate's loss; the figures are the
// references' at 5 and 20 KB (llvmpipe, docs/simplify.md), with what the grown cage then scored.
#include <gtest/gtest.h>

#include "simplify/budget_search.h"

namespace subdfit::simplify {
namespace {

BudgetCandidate bareCage(int faces, std::uintmax_t bytes, double loss) {
    BudgetCandidate c;
    c.faces = faces;
    c.bytes = bytes;
    c.monitorLoss = loss;
    return c;
}

TEST(BareGrowth, IsTriedWhereTheGrownCageReachedTheBest) {
    // Against the ladder's best, as the search weighs them. The relief bishop at 5 KB: 1 247
    // faces (0.01105) against 779 with heights (0.004668); grown to 2 872 faces at 10 bits the
    // bare cage scored 0.004638. The Stanford bunny at 5 KB: 0.001376 against 0.0006137, grown
    // 0.000579. The relief pawn at 20 KB: 0.001437 against 0.0008526, grown 0.000862.
    EXPECT_TRUE(bareMayReach(bareCage(1247, 3429, 0.01105), 0.004668, 5000));
    EXPECT_TRUE(bareMayReach(bareCage(1250, 3537, 0.001376), 0.0006137, 5000));
    EXPECT_TRUE(bareMayReach(bareCage(7999, 17925, 0.001437), 0.0008526, 20000));
}

TEST(BareGrowth, IsNotTriedWhereTheGrownCageStillTrailed) {
    // The README demo at 20 KB: 7 999 faces (18 174 B) against 0.000396; grown to 14 289 faces
    // 0.000790, as quads 0.000709. The relief Spot at 5 KB: 0.01449 against 0.003403, grown
    // 0.007692; the relief pawn at 5 KB: 0.01632 against 0.005481, grown 0.008506.
    EXPECT_FALSE(bareMayReach(bareCage(7999, 18174, 0.001306), 0.000396, 20000));
    EXPECT_FALSE(bareMayReach(bareCage(1247, 3504, 0.01449), 0.003403, 5000));
    EXPECT_FALSE(bareMayReach(bareCage(1246, 3506, 0.01632), 0.005481, 5000));
}

TEST(BareGrowth, ACageThatFillsTheBudgetAtTheFewestBitsIsNotGrownBeyondIt) {
    // Already at the budget with 10-bit positions: no growth is counted on, only the slack.
    BudgetCandidate full = bareCage(4000, 10000, 0.001);
    full.positionBits = 10;
    EXPECT_TRUE(bareMayReach(full, 0.001 / kBareGrowthSlack * 1.01, 10000));
    EXPECT_FALSE(bareMayReach(full, 0.001 / kBareGrowthSlack * 0.99, 10000));
}

}  // namespace
}  // namespace subdfit::simplify
