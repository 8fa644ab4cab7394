#include "io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <memory>

#include "util/error.h"

namespace subdfit::io {

namespace fs = std::filesystem;

namespace {

// The longest file name the folders subdfit writes to take (NAME_MAX on Linux file systems).
constexpr std::size_t kMaxFileName = 255;

// ".NAME.tmpPID_N.EXT" beside the destination: hidden, unique, and with the real extension last;
// NAME cut short where the whole would pass kMaxFileName (the destination's own name fits).
fs::path temporaryName(const fs::path& destination) {
    static std::atomic<unsigned> counter{0};
    const std::string tag = ".tmp" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
    const std::string extension = destination.extension().string();
    std::string stem = destination.stem().string();
    const std::size_t room = kMaxFileName - std::min(kMaxFileName, 1 + tag.size() + extension.size());
    if (stem.size() > room) stem.resize(room);
    std::string name(1, '.');  // appended piece by piece: GCC 12 misreads "." + string (-Wrestrict)
    name += stem;
    name += tag;
    name += extension;
    return destination.parent_path() / name;
}

bool syncPath(const fs::path& path, int flags) {
    const int fd = ::open(path.empty() ? "." : path.c_str(), flags | O_CLOEXEC);
    if (fd < 0) return false;
    const bool ok = ::fsync(fd) == 0;
    ::close(fd);
    return ok;
}

}  // namespace

std::string outputFileProblem(const fs::path& destination) {
    std::error_code ec;
    const fs::file_status status = fs::symlink_status(destination, ec);
    if (ec || !fs::exists(status) || fs::is_regular_file(status)) return "";  // nothing there, or a file to replace
    if (fs::is_directory(status)) return "is a folder, not a file";
    if (fs::is_symlink(status)) return "is a symlink: subdfit replaces only regular files";
    return "is not a regular file (a FIFO, device or socket): subdfit replaces only regular files";
}

void checkOutputFile(const fs::path& destination, const fs::path& input) {
    if (destination.empty()) throw Error("the output path is empty");
    if (const std::size_t length = destination.filename().string().size(); length > kMaxFileName)
        throw fileError(destination.string(), "its name is " + std::to_string(length) + " bytes, more than the " +
                                                  std::to_string(kMaxFileName) + " a file name may have");
    if (const std::string problem = outputFileProblem(destination); !problem.empty())
        throw fileError(destination.string(), problem);
    std::error_code ec;
    if (!input.empty() && fs::equivalent(destination, input, ec))
        throw fileError(destination.string(), "is the input " + input.string() + ": write the output elsewhere");
}

AtomicFile::AtomicFile(fs::path destination) : destination_(std::move(destination)) {
    if (destination_.empty()) throw Error("the output path is empty");
    if (const std::string problem = outputFileProblem(destination_); !problem.empty()) fail(problem);
    for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
        temporary_ = temporaryName(destination_);
        fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd_ < 0 && errno != EEXIST) break;
    }
    if (fd_ < 0) {
        temporary_.clear();
        fail(std::string("cannot create a temporary file beside it: ") + std::strerror(errno));
    }
}

AtomicFile::~AtomicFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

void AtomicFile::write(std::string_view bytes) {
    while (!bytes.empty()) {
        const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) fail(std::string("cannot write: ") + std::strerror(errno));
        bytes.remove_prefix(size_t(n));
    }
}

void AtomicFile::commit() {
    // fsync before the rename: a rename that outlives a crash must not point at unwritten data.
    if (fd_ >= 0) {
        if (::fsync(fd_) != 0) fail(std::string("cannot write: ") + std::strerror(errno));
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0) fail(std::string("cannot write: ") + std::strerror(errno));
    } else if (!syncPath(temporary_, O_RDONLY)) {
        fail(std::string("cannot write: ") + std::strerror(errno));
    }
    if (const std::string problem = outputFileProblem(destination_); !problem.empty()) fail(problem);
    if (::rename(temporary_.c_str(), destination_.c_str()) != 0)
        fail(std::string("cannot replace: ") + std::strerror(errno));
    temporary_.clear();
    // The rename lives in the folder: sync it too (best effort; some filesystems refuse).
    syncPath(destination_.parent_path(), O_RDONLY | O_DIRECTORY);
}

void AtomicFile::fail(const std::string& what) const { throw fileError(destination_.string(), what); }

void writeAtomically(const fs::path& destination, const std::function<void(const fs::path&)>& write) {
    AtomicFile file(destination);
    ::close(file.fd_);  // the writer opens the temporary by name; commit() syncs it by name
    file.fd_ = -1;
    try {
        write(file.temporary_);
    } catch (const fs::filesystem_error& e) {
        file.fail("could not write: " + e.code().message());
    }
    file.commit();
}

void writeTextAtomically(const fs::path& destination, std::string_view text) {
    AtomicFile file(destination);
    file.write(text);
    file.commit();
}

void writeFilesTogether(const std::vector<std::pair<fs::path, std::string_view>>& files) {
    std::vector<std::unique_ptr<AtomicFile>> written;
    for (const auto& [destination, bytes] : files) {
        written.push_back(std::make_unique<AtomicFile>(destination));
        written.back()->write(bytes);
    }
    for (auto& file : written) file->commit();
}

}  // namespace subdfit::io
