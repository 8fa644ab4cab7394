// gl::TimestampLog, which step-cost uses to say where a step's time goes: with either clock,
// phases come back in the order first marked, one value per round, a phase marked twice in a round
// adds up, and one first marked in a later round reads 0 in the rounds before it.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gl/timestamp_log.h"
#include "gl_test_context.h"
#include "optim/updates.h"

namespace subdfit::gl {
namespace {

TEST(TimestampLog, PhasesInFirstMarkedOrderOneValuePerRound) {
    test::programs();  // the context
    optim::ParameterGroup group(optim::GroupKind::Other, "x", std::vector<float>(100'000, 0.0f),
                                optim::GroupSettings{1.0f});
    for (PhaseClock clock : {PhaseClock::GpuTimestamp, PhaseClock::HostAfterFinish}) {
        TimestampLog log(clock);
        for (int round = 0; round < 2; ++round) {
            log.begin();
            optim::perturb(test::programs(), group, 1u, 2u);
            log.mark("perturb");
            log.mark("nothing");
            optim::perturb(test::programs(), group, 3u, 4u);
            log.mark("perturb");
            if (round == 1) log.mark("late");
            glFinish();
        }
        const auto phases = log.collect();
        ASSERT_EQ(phases.size(), 3u);
        EXPECT_EQ(phases[0].first, "perturb");
        EXPECT_EQ(phases[1].first, "nothing");
        EXPECT_EQ(phases[2].first, "late");
        for (const auto& [phase, ms] : phases) {
            ASSERT_EQ(ms.size(), 2u) << phase;
            for (double value : ms) {
                EXPECT_TRUE(std::isfinite(value)) << phase;
                EXPECT_GE(value, 0.0) << phase;
            }
        }
        EXPECT_EQ(phases[2].second[0], 0.0);  // not marked in the first round
    }
    test::expectNoGlError();
}

}  // namespace
}  // namespace subdfit::gl
