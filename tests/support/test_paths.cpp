#include "test_paths.h"

namespace subdfit::test {

std::filesystem::path assetPath(const std::string& relative) {
    return std::filesystem::path(SUBDFIT_SOURCE_DIR) / "assets" / relative;
}

std::filesystem::path sharedAssetPath(const std::string& relative) {
    auto p = std::filesystem::path(SUBDFIT_SHARED_ASSETS) / relative;
    return std::filesystem::exists(p) ? p : std::filesystem::path();
}

std::filesystem::path scratchDir(const std::string& name) {
    auto p = std::filesystem::current_path() / "scratch" / name;
    std::filesystem::remove_all(p);
    std::filesystem::create_directories(p);
    return p;
}

}  // namespace subdfit::test
