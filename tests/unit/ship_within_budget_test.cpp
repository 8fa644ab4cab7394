// shipWithinBudget: an asset over its budget is coded again, from what it held before coding, at
// fewer map bits until it fits. Coded once, every height is within half of the coarser step of
// its value; the file decoded and coded again would carry the first coding's error too.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "codec/node_coding.h"
#include "codec/subd_format.h"
#include "io/output_file.h"
#include "simplify/budget_search.h"
#include "noisy_heights.h"
#include "test_paths.h"

namespace subdfit::simplify {
namespace {

TEST(ShipWithinBudget, CodesTheAssetAgainAtFewerBitsOnce) {
    const auto dir = test::scratchDir("ship_within_budget");
    const std::filesystem::path subd = dir / "asset.subd";
    const codec::SubdAsset asset = test::noisyHeightsSphere(6, 0.05f, 7);
    const auto at = [&](int bits) { return codec::encodeSubd(asset, codec::SubdPrecision::forMapBits(bits)); };
    const std::uintmax_t written = io::writeBytes(subd, at(8)).bytes;
    const std::uintmax_t budget = at(6).size();
    ASSERT_GT(written, budget);
    ASSERT_GT(at(7).size(), budget) << "7 bits must not fit, for the ladder to reach 6";

    const BudgetShipment shipped = shipWithinBudget(asset, subd, written, budget, 8, 14, 90);
    EXPECT_EQ(shipped.mapBits, 6);
    EXPECT_EQ(shipped.bytes, std::filesystem::file_size(subd));
    EXPECT_LE(shipped.bytes, budget);
    const codec::SubdAsset decoded = codec::readSubd(subd);
    const auto& heights = asset.maps.displacement;
    ASSERT_EQ(decoded.maps.displacement.size(), heights.size());
    const float step = codec::quantisationFor(heights, 1, 0, 6).step;
    float worst = 0.0f;
    for (size_t n = 0; n < heights.size(); ++n)
        worst = std::max(worst, std::abs(decoded.maps.displacement[n] - heights[n]));
    EXPECT_LE(worst, 0.5f * step * 1.001f);
}

}  // namespace
}  // namespace subdfit::simplify
