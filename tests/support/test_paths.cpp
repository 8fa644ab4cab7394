#include "test_paths.h"

#include <unistd.h>

namespace subdfit::test {

std::filesystem::path assetPath(const std::string& relative) {
    return std::filesystem::path(SUBDFIT_SOURCE_DIR) / "assets" / relative;
}

std::filesystem::path sharedAssetPath(const std::string& relative) {
    auto p = std::filesystem::path(SUBDFIT_SHARED_ASSETS) / relative;
    if (std::filesystem::exists(p)) return p;
    // The OpenSubdiv shapes are also bundled (license allows), so a user's clone runs those tests.
    if (relative.rfind("osd-shapes", 0) == 0 && std::filesystem::exists(assetPath(relative)))
        return assetPath(relative);
    return {};
}

std::filesystem::path scratchDir(const std::string& name) {
    // Under the build tree whatever folder the test runs from: never litter the sources. The
    // process id keeps tests of one suite apart when ctest runs them as parallel processes
    // (each re-runs the suite's set-up, which would otherwise wipe the other's files).
    auto p = std::filesystem::path(SUBDFIT_SCRATCH_DIR) / (name + "." + std::to_string(getpid()));
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
}

}  // namespace subdfit::test
