#include "io/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#define XXH_STATIC_LINKING_ONLY  // XXH3_state_t on the stack
#include <xxhash.h>

#include <cerrno>
#include <cstring>

#include "util/error.h"
#include "util/hash.h"
#include "util/interrupt.h"

namespace subdfit::io {
namespace {

class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

std::string sizeProblem(std::uint64_t size, std::uint64_t maxBytes) {
    return "is " + std::to_string(size) + " bytes, more than the " + std::to_string(maxBytes) + "-byte input limit";
}

// "" for a regular file within the limit.
std::string statProblem(const struct stat& st, std::uint64_t maxBytes) {
    if (S_ISDIR(st.st_mode)) return "is a folder, not a file";
    if (!S_ISREG(st.st_mode)) return "is not a regular file (a FIFO, device or socket)";
    if (std::uint64_t(st.st_size) > maxBytes) return sizeProblem(std::uint64_t(st.st_size), maxBytes);
    return "";
}

}  // namespace

std::string inputFileProblem(const std::filesystem::path& path, std::uint64_t maxBytes) {
    struct stat st {};
    if (stat(path.c_str(), &st) != 0) return std::string("cannot open: ") + std::strerror(errno);
    return statProblem(st, maxBytes);
}

void readInputFile(const std::filesystem::path& path, const std::function<void(std::string_view)>& consume,
                   std::uint64_t maxBytes) {
    const std::string name = path.string();
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer that never comes.
    const Descriptor file(open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
    if (file.get() < 0) throw fileError(name, std::string("cannot open: ") + std::strerror(errno));
    struct stat st {};
    if (fstat(file.get(), &st) != 0) throw fileError(name, std::string("cannot stat: ") + std::strerror(errno));
    if (const std::string problem = statProblem(st, maxBytes); !problem.empty()) throw fileError(name, problem);

    char chunk[1 << 16];
    std::uint64_t total = 0;
    for (;;) {
        throwIfStopRequested();
        const ssize_t n = read(file.get(), chunk, sizeof chunk);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw fileError(name, std::string("cannot read: ") + std::strerror(errno));
        }
        if (n == 0) break;
        total += std::uint64_t(n);
        if (total > maxBytes) throw fileError(name, sizeProblem(total, maxBytes));  // it grew while read
        consume(std::string_view(chunk, size_t(n)));
    }
}

std::string readInputFile(const std::filesystem::path& path, std::uint64_t maxBytes) {
    std::string bytes;
    std::error_code sizeError;
    if (const auto size = std::filesystem::file_size(path, sizeError); !sizeError && size <= maxBytes)
        bytes.reserve(size);
    readInputFile(
        path, [&](std::string_view chunk) { bytes.append(chunk); }, maxBytes);
    return bytes;
}

std::string fileDigest(const std::filesystem::path& path) {
    XXH3_state_t state;
    XXH3_128bits_reset(&state);
    readInputFile(path, [&](std::string_view chunk) { XXH3_128bits_update(&state, chunk.data(), chunk.size()); });
    const XXH128_hash_t digest = XXH3_128bits_digest(&state);
    return hexDigits(digest.high64) + hexDigits(digest.low64);
}

}  // namespace subdfit::io
