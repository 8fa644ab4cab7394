// A broken internal contract is an exception, not an abort: a batch goes on to its next asset
// and a run removes its temp files on the way out.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>

#include "util/error.h"

namespace subdfit::test {
namespace {

int checkedHalf(int even) {
    SUBDFIT_CHECK(even % 2 == 0);
    return even / 2;
}

TEST(InternalCheck, AFailedCheckThrowsNamingTheConditionAndWhereItIs) {
    EXPECT_EQ(checkedHalf(4), 2);
    try {
        checkedHalf(3);
        FAIL() << "no exception";
    } catch (const InternalError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("even % 2 == 0"), std::string::npos) << message;
        EXPECT_NE(message.find("internal_check_test.cpp"), std::string::npos) << message;
    }
    // Not an input error: nothing that catches those mistakes it for a bad file.
    EXPECT_FALSE((std::is_base_of_v<Error, InternalError>));
}

}  // namespace
}  // namespace subdfit::test
