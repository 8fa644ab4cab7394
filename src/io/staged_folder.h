#pragma once
// Results that appear together or not at all: written into DIR/.staging-PID/, moved into DIR
// by commit(). Without a commit (an exception, a stop request) the staging folder is removed
// and DIR keeps what it had.
#include <filesystem>

namespace subdfit::io {

class StagedFolder {
public:
    // Creates DIR (if needed) and the staging folder, removing what earlier runs that died
    // before their commit left there.
    explicit StagedFolder(std::filesystem::path dir);
    ~StagedFolder();
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;

    const std::filesystem::path& path() const { return staging_; }

    // Moves every entry into DIR, replacing what is there by that name.
    void commit();

private:
    std::filesystem::path dir_, staging_;
    bool committed_ = false;
};

}  // namespace subdfit::io
