#include "mesh/obj_writer.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>

#include "mesh/obj_tags.h"
#include "util/error.h"

namespace subdfit::mesh {

namespace {

// A file descriptor for the temporary file; unless released by commit(), the file is removed.
class TempFile {
public:
    explicit TempFile(const std::filesystem::path& target) : target_(target.string()) {
        // Unique per process and call, in the target's folder so that rename() is atomic.
        static std::atomic<unsigned> counter{0};
        for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
            std::string temp(1, '.');
            temp += target.filename().string();
            temp += ".tmp" + std::to_string(::getpid()) + '_' + std::to_string(counter++);
            auto name = target;
            name.replace_filename(temp);
            fd_ = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
            if (fd_ >= 0) name_ = name.string();
            else if (errno != EEXIST) break;
        }
        if (fd_ < 0) fail("cannot create a temporary file beside it");
    }
    ~TempFile() {
        if (fd_ >= 0) ::close(fd_);
        if (!name_.empty()) ::unlink(name_.c_str());
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;

    void write(std::string_view bytes) {
        while (!bytes.empty()) {
            const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
            if (n < 0 && errno == EINTR) continue;
            if (n <= 0) fail("cannot write");
            bytes.remove_prefix(size_t(n));
        }
    }

    void commit() {
        // fsync first: a rename that outlives a crash must not point at unwritten data.
        if (::fsync(fd_) != 0) fail("cannot write");
        const int fd = fd_;
        fd_ = -1;
        if (::close(fd) != 0) fail("cannot write");
        if (::rename(name_.c_str(), target_.c_str()) != 0) fail("cannot replace");
        name_.clear();
    }

private:
    [[noreturn]] void fail(const char* what) {
        throw fileError(target_, std::string(what) + ": " + std::strerror(errno));
    }

    std::string target_, name_;
    int fd_ = -1;
};

// Shortest text that reads back as the same float (std::to_chars' round-trip guarantee).
void appendFloat(std::string& out, float value) {
    char buf[32];
    const auto result = std::to_chars(buf, buf + sizeof buf, value);
    out.append(buf, result.ptr);
}

void appendInt(std::string& out, int value) {
    char buf[16];
    const auto result = std::to_chars(buf, buf + sizeof buf, value);
    out.append(buf, result.ptr);
}

}  // namespace

void writeObj(const std::filesystem::path& path, const PolygonMesh& mesh) {
    const std::string name = path.string();
    // Refused before anything is created: a file we could not read back is not worth writing.
    for (const glm::vec3& p : mesh.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw fileError(name, "cannot write a non-finite vertex coordinate");

    size_t indexCount = 0;
    for (const int n : mesh.faceSizes) indexCount += size_t(n);
    SUBDFIT_CHECK(indexCount == mesh.faceIndices.size());

    TempFile file(path);
    constexpr size_t kFlushAt = 1 << 20;
    std::string out = "# subdfit cage: " + std::to_string(mesh.vertexCount()) + " vertices, " +
                      std::to_string(mesh.faceCount()) + " faces\n";
    for (const glm::vec3& p : mesh.positions) {
        out += "v ";
        appendFloat(out, p.x);
        out += ' ';
        appendFloat(out, p.y);
        out += ' ';
        appendFloat(out, p.z);
        out += '\n';
        if (out.size() > kFlushAt) file.write(out), out.clear();
    }
    size_t first = 0;
    for (const int n : mesh.faceSizes) {
        out += 'f';
        for (int k = 0; k < n; ++k) {
            out += ' ';
            appendInt(out, mesh.faceIndices[first + size_t(k)] + 1);
        }
        out += '\n';
        first += size_t(n);
        if (out.size() > kFlushAt) file.write(out), out.clear();
    }
    out += obj::formatTagLines(mesh.tags);
    file.write(out);
    file.commit();
}

}  // namespace subdfit::mesh
