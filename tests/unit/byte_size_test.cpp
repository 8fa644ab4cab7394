// `--budget`'s sizes: decimal with K/M/G/T (1000s) or KiB..TiB (1024s), 100 bytes to 1 TB;
// anything strtod would have read besides (hex, exponents, signs, spaces) is refused, and a
// size out of range is refused the same way (one kind of error, one exit code).
#include <gtest/gtest.h>

#include "common/byte_size.h"

namespace subdfit::apps {
namespace {

std::optional<std::uintmax_t> parsed(const std::string& text) {
    std::string problem;
    const auto size = parseByteSize(text, problem);
    EXPECT_EQ(size.has_value(), problem.empty()) << text << ": " << problem;
    return size;
}

TEST(ByteSize, ReadsDecimalSizesWithUnitsUpToATerabyte) {
    EXPECT_EQ(parsed("20000"), 20000u);
    EXPECT_EQ(parsed("20KB"), 20000u);
    EXPECT_EQ(parsed("20k"), 20000u);
    EXPECT_EQ(parsed("1.5MB"), 1500000u);
    EXPECT_EQ(parsed("2KiB"), 2048u);
    EXPECT_EQ(parsed("2G"), 2000000000u);
    EXPECT_EQ(parsed("1TB"), 1000000000000u);
    EXPECT_EQ(parsed("1.5gib"), 1610612736u);
    EXPECT_EQ(parsed("100"), 100u);
}

TEST(ByteSize, RefusesWhatIsNotADecimalSizeInRange) {
    for (const char* text : {"0x100", "1e3", "1E6", "-5", "+500", " 200", "200 ", "20 parsecs", "KB", "", ".", "nan",
                             "inf", "50", "0", "1.1TB", "2TiB", "99.4"}) {
        std::string problem;
        EXPECT_FALSE(parseByteSize(text, problem).has_value()) << "'" << text << "' was read";
        EXPECT_FALSE(problem.empty()) << text;
    }
    std::string problem;
    parseByteSize("50", problem);
    EXPECT_NE(problem.find("100 bytes to 1 TB"), std::string::npos) << problem;
}

}  // namespace
}  // namespace subdfit::apps
