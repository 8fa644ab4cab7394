// Batch output names: whatever a manifest says, a name stays inside --out, is unique per asset,
// and does not depend on the order of the lines.
#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <set>

#include "simplify/batch.h"

namespace subdfit::simplify {
namespace {

namespace fs = std::filesystem;

bool isSafeName(const std::string& name) {
    static const std::regex safe("[A-Za-z0-9_][A-Za-z0-9._-]{0,63}-[0-9a-f]{12}");
    return std::regex_match(name, safe);
}

TEST(BatchNames, HostileLabelsGiveSafeNames) {
    const std::string labels[] = {"..",
                                  ".",
                                  "...",
                                  "",
                                  "../../etc/passwd",
                                  "/abs/path",
                                  "a/b\\c",
                                  "tab\there",
                                  "new\nline",
                                  std::string("nul\0x", 5),
                                  "caf\xc3\xa9",
                                  std::string(300, 'x'),
                                  ".hidden",
                                  "-dash",
                                  "a:b*c?d"};
    for (const std::string& label : labels) {
        const std::string name = assetName(label, "identity");
        EXPECT_TRUE(isSafeName(name)) << "label '" << label << "' gave '" << name << "'";
        EXPECT_NE(name.front(), '.');
    }
    EXPECT_TRUE(assetName("props/crate", "x").starts_with("props_crate-"));
}

TEST(BatchNames, TheIdentityMakesTheNameUnique) {
    EXPECT_NE(assetName("a", "one"), assetName("a", "two"));
    EXPECT_EQ(assetName("a", "one"), assetName("a", "one"));
}

std::vector<BatchItem> itemsFor(const std::vector<std::string>& references, int faces = 1000) {
    std::vector<BatchItem> items;
    int line = 0;
    for (const auto& reference : references) {
        SimplifyOptions options;
        options.fit.reference = fs::path("/manifests") / reference;
        options.faces = faces;
        items.push_back({.options = options, .line = ++line});
    }
    return items;
}

std::vector<std::string> names(std::vector<BatchItem> items, const std::vector<std::string>& written) {
    nameItems(items, {written.begin(), written.end()});
    std::vector<std::string> out;
    for (const auto& item : items) out.push_back(item.name);
    return out;
}

// The case: the old scheme named these a, a_2, a_2 and skipped the third as done.
TEST(BatchNames, SameStemsInOtherFoldersDoNotCollide) {
    const std::vector<std::string> written = {"x/a.obj", "y/a.obj", "a_2.obj"};
    const auto got = names(itemsFor(written), written);
    ASSERT_EQ(got.size(), 3u);
    EXPECT_EQ(std::set<std::string>(got.begin(), got.end()).size(), 3u);
    for (const auto& name : got) EXPECT_TRUE(isSafeName(name)) << name;

    // Reordering the manifest names every asset the same.
    const std::vector<std::string> reversed(written.rbegin(), written.rend());
    auto again = names(itemsFor(reversed), reversed);
    std::reverse(again.begin(), again.end());
    EXPECT_EQ(again, got);
}

TEST(BatchNames, OtherSettingsAreAnotherAsset) {
    const std::vector<std::string> written = {"a.obj"};
    EXPECT_NE(names(itemsFor(written, 200), written), names(itemsFor(written, 300), written));
}

TEST(BatchNames, ARepeatedAssetIsDoneOnce) {
    const std::vector<std::string> written = {"a.obj", "b.obj", "./a.obj"};
    auto items = itemsFor(written);
    const auto dropped = nameItems(items, {written.begin(), written.end()});
    ASSERT_EQ(items.size(), 2u);
    ASSERT_EQ(dropped.size(), 1u);
    EXPECT_NE(dropped[0].find("line 3"), std::string::npos) << dropped[0];
    EXPECT_NE(dropped[0].find("line 1"), std::string::npos) << dropped[0];
}

}  // namespace
}  // namespace subdfit::simplify
