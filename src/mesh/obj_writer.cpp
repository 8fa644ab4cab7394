#include "mesh/obj_writer.h"

#include <charconv>
#include <cmath>

#include "io/atomic_file.h"
#include "mesh/obj_tags.h"
#include "util/error.h"

namespace subdfit::mesh {

namespace {

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

    io::AtomicFile file(path);
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
