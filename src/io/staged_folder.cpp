#include "io/staged_folder.h"

#include <unistd.h>

#include <string>

#include "util/error.h"

namespace subdfit::io {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kPrefix = ".staging-";

}  // namespace

StagedFolder::StagedFolder(fs::path dir) : dir_(std::move(dir)) {
    fs::create_directories(dir_);
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir_, ec))
        if (entry.path().filename().string().starts_with(kPrefix)) fs::remove_all(entry.path(), ec);
    staging_ = dir_ / (std::string(kPrefix) + std::to_string(getpid()));
    fs::create_directory(staging_);
}

StagedFolder::~StagedFolder() {
    std::error_code ignored;
    if (!committed_) fs::remove_all(staging_, ignored);
}

void StagedFolder::commit() {
    for (const auto& entry : fs::directory_iterator(staging_)) {
        const fs::path target = dir_ / entry.path().filename();
        // rename() replaces a file but not a non-empty folder (a previous run's baselines/).
        if (fs::is_directory(fs::symlink_status(target)) && entry.is_directory()) fs::remove_all(target);
        fs::rename(entry.path(), target);
    }
    fs::remove(staging_);
    committed_ = true;
}

}  // namespace subdfit::io
