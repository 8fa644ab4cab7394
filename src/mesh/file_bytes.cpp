#include "mesh/file_bytes.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "util/error.h"

namespace subdfit::mesh {

namespace {
struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
}  // namespace

std::string readFileBytes(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw fileError(name, "is a folder, not a file");

    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(name.c_str(), "rb"));
    if (!file) throw fileError(name, std::string("cannot open: ") + std::strerror(errno));

    // Read in chunks rather than trusting a size from seek/tell, which pipes and /proc lack.
    std::string bytes;
    std::error_code sizeError;
    if (const auto size = std::filesystem::file_size(path, sizeError); !sizeError) bytes.reserve(size);
    char chunk[1 << 16];
    for (;;) {
        const size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
        bytes.append(chunk, n);
        if (n < sizeof chunk) break;
    }
    if (std::ferror(file.get())) throw fileError(name, std::string("cannot read: ") + std::strerror(errno));
    return bytes;
}

}  // namespace subdfit::mesh
