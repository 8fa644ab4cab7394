#include "fit/state_blend.h"

#include <gtest/gtest.h>

namespace subdfit::fit {
namespace {

TEST(StateBlend, BetweenIsTheStraightWayFromOneStateToTheOther) {
    FitState from, to;
    from.groups = {{.theta = {0.0f, 2.0f}}, {.theta = {-1.0f}}};
    to.groups = {{.theta = {4.0f, 2.0f}, .moment1 = {1.0f, 1.0f}}, {.theta = {1.0f}}};
    to.steps = 7;
    const FitState half = between(from, to, 0.5f);
    EXPECT_EQ(half.groups[0].theta, (std::vector<float>{2.0f, 2.0f}));
    EXPECT_EQ(half.groups[1].theta, (std::vector<float>{0.0f}));
    EXPECT_EQ(half.groups[0].moment1, to.groups[0].moment1);  // the rest is `to`'s
    EXPECT_EQ(half.steps, 7);
    EXPECT_EQ(between(from, to, 0.0f).groups[0].theta, from.groups[0].theta);
    EXPECT_EQ(between(from, to, 1.0f).groups[0].theta, to.groups[0].theta);
}

TEST(StateBlend, TheFurthestThatHoldsIsBisectedBelowTheEdge) {
    std::vector<float> tried;
    const float t = furthestThatHolds(
        [&](float t) {
            tried.push_back(t);
            return t <= 0.3f;
        },
        4);
    EXPECT_EQ(tried, (std::vector<float>{0.5f, 0.25f, 0.375f, 0.3125f}));
    EXPECT_FLOAT_EQ(t, 0.25f);  // within a sixteenth below the edge, never above it
    EXPECT_EQ(furthestThatHolds([](float) { return false; }, 4), 0.0f);
    EXPECT_FLOAT_EQ(furthestThatHolds([](float) { return true; }, 3), 0.875f);
}

}  // namespace
}  // namespace subdfit::fit
