#pragma once
#include <filesystem>
#include <string>

namespace subdfit::test {

// A file bundled in the repository's assets/.
std::filesystem::path assetPath(const std::string& relative);
// A file in ../shared/assets-ext (development set), else its bundled copy in assets/ when there
// is one (the OpenSubdiv shapes); empty path when neither is there.
std::filesystem::path sharedAssetPath(const std::string& relative);
// A fresh, empty scratch folder under the build tree (build/tests/scratch/NAME.PID) for one test.
std::filesystem::path scratchDir(const std::string& name);

}  // namespace subdfit::test

// Skips the current test with a message when a shared (non-bundled) asset is missing.
#define SUBDFIT_REQUIRE_SHARED(var, relative)                    \
    const auto var = ::subdfit::test::sharedAssetPath(relative); \
    if (var.empty()) GTEST_SKIP() << "shared asset " << (relative) << " not found (only in the development checkout)"
