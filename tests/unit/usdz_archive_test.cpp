// The .usdz container and the .usda numbers, read back byte by byte: stored entries whose data
// start on 64-byte boundaries, with sound checksums and a central directory that finds them;
// floats that read back to the very same float.
#include <gtest/gtest.h>

#include <zlib.h>

#include <charconv>
#include <cstring>

#include "export/usd/usda_text.h"
#include "export/usd/usdz_archive.h"
#include "util/error.h"

namespace subdfit {
namespace {

template <class T>
T field(const std::vector<unsigned char>& bytes, size_t at) {
    T value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    return value;
}

TEST(UsdzArchive, EntriesAreStoredAlignedAndFoundByTheDirectory) {
    std::vector<exporter::UsdzEntry> entries{{"asset.usda", std::vector<unsigned char>(1001, 'a')},
                                             {"displacement.png", std::vector<unsigned char>(77, 7)},
                                             {"a/longer/name.png", std::vector<unsigned char>(3, 9)}};
    const auto zip = exporter::usdzArchive(entries);
    // The end of central directory record: the entries and where the directory starts.
    const size_t end = zip.size() - 22;
    ASSERT_EQ(field<std::uint32_t>(zip, end), 0x06054b50u);
    ASSERT_EQ(field<std::uint16_t>(zip, end + 10), entries.size());
    size_t central = field<std::uint32_t>(zip, end + 16);
    for (const auto& entry : entries) {
        ASSERT_EQ(field<std::uint32_t>(zip, central), 0x02014b50u);
        const size_t local = field<std::uint32_t>(zip, central + 42);
        const size_t nameBytes = field<std::uint16_t>(zip, central + 28);
        EXPECT_EQ(std::string(reinterpret_cast<const char*>(zip.data() + central + 46), nameBytes), entry.name);
        central += 46 + nameBytes;

        ASSERT_EQ(field<std::uint32_t>(zip, local), 0x04034b50u);
        EXPECT_EQ(field<std::uint16_t>(zip, local + 8), 0u);  // stored
        EXPECT_EQ(field<std::uint32_t>(zip, local + 18), entry.bytes.size());
        EXPECT_EQ(field<std::uint32_t>(zip, local + 22), entry.bytes.size());
        const size_t data = local + 30 + field<std::uint16_t>(zip, local + 26) + field<std::uint16_t>(zip, local + 28);
        EXPECT_EQ(data % 64, 0u) << entry.name;
        ASSERT_LE(data + entry.bytes.size(), zip.size());
        EXPECT_EQ(std::memcmp(zip.data() + data, entry.bytes.data(), entry.bytes.size()), 0) << entry.name;
        EXPECT_EQ(field<std::uint32_t>(zip, local + 14), crc32(0L, entry.bytes.data(), uInt(entry.bytes.size())));
    }
    EXPECT_EQ(central, end);
}

TEST(UsdzArchive, RefusesRepeatedOrEmptyNamesAndNoEntries) {
    const std::vector<exporter::UsdzEntry> twice{{"a.usda", {1}}, {"a.usda", {2}}};
    EXPECT_THROW(exporter::usdzArchive(twice), Error);
    const std::vector<exporter::UsdzEntry> unnamed{{"", {1}}};
    EXPECT_THROW(exporter::usdzArchive(unnamed), Error);
    EXPECT_THROW(exporter::usdzArchive({}), Error);
}

TEST(UsdaText, NumbersReadBackToTheSameFloat) {
    for (float value : {0.1f, 1.0f / 3.0f, -123456.789f, 1e-30f, 3.4e38f, 0.0f, 10.0f}) {
        const std::string text = exporter::usda::number(value);
        float back = 0.0f;
        std::from_chars(text.data(), text.data() + text.size(), back);
        EXPECT_EQ(back, value) << text;
    }
    EXPECT_EQ(exporter::usda::tuple(glm::vec2(0.5f, 2.0f)), "(0.5, 2)");
    EXPECT_EQ(exporter::usda::quoted("a \"b\" \\c"), "\"a \\\"b\\\" \\\\c\"");
}

}  // namespace
}  // namespace subdfit
