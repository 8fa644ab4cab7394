#pragma once
// An exclusive lock that dies with its holder: flock(2) on a lock file, released when the
// descriptor closes, and by the kernel when the process ends however it ends (SIGKILL
// included), so a crashed holder never blocks the next run. The lock file itself stays (removing
// it would let a third process lock a new file while the second still holds the old one).
#include <filesystem>
#include <optional>

namespace subdfit::io {

class FileLock {
public:
    // The lock, or nothing when another process holds it. Creates the file (and its folder).
    // Throws subdfit::Error naming the file when it cannot be created or locked.
    static std::optional<FileLock> tryAcquire(const std::filesystem::path& path);

    FileLock(FileLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
    FileLock& operator=(FileLock&&) = delete;
    FileLock(const FileLock&) = delete;
    ~FileLock();

private:
    explicit FileLock(int fd) : fd_(fd) {}
    int fd_;
};

}  // namespace subdfit::io
