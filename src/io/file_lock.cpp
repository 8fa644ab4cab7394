#include "io/file_lock.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "util/error.h"

namespace subdfit::io {

std::optional<FileLock> FileLock::tryAcquire(const std::filesystem::path& path) {
    std::filesystem::create_directories(path.parent_path());
    // O_NOFOLLOW: a lock file planted as a symlink must not make us create files elsewhere.
    const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd < 0) throw fileError(path.string(), std::string("cannot open the lock file: ") + std::strerror(errno));
    if (flock(fd, LOCK_EX | LOCK_NB) == 0) return FileLock(fd);
    const int error = errno;
    close(fd);
    if (error == EWOULDBLOCK) return std::nullopt;
    throw fileError(path.string(), std::string("cannot lock: ") + std::strerror(error));
}

FileLock::~FileLock() {
    if (fd_ >= 0) close(fd_);
}

}  // namespace subdfit::io
