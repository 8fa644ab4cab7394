#include "mesh/obj_reader.h"

#include <cmath>
#include <cstdint>

#include "io/input_file.h"
#include "mesh/input_limits.h"
#include "mesh/obj_tags.h"
#include "mesh/obj_tokens.h"
#include "util/interrupt.h"

namespace subdfit::mesh {

namespace {

using obj::LineContext;
using obj::quoted;
using obj::Tokens;

// Parses lines in file order; checks that need the whole file wait for finish().
class ObjParser {
public:
    explicit ObjParser(PolygonMesh& mesh) : mesh_(mesh), at_{mesh.sourcePath, 0} {}

    void parse(std::string_view text) {
        while (!text.empty()) {
            if (++at_.line % 65536 == 0) throwIfStopRequested();
            const size_t eol = text.find('\n');
            const std::string_view line = text.substr(0, eol);
            text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
            parseLine(line);
        }
    }

    void finish() {
        const std::string& path = mesh_.sourcePath;
        if (mesh_.faceSizes.empty()) throw fileError(path, "no faces (empty mesh)");
        if (maxIndex_ >= mesh_.vertexCount())
            LineContext{path, maxIndexLine_}.fail(
                "face index " + std::to_string(maxIndex_ + 1) + " is out of range (the file has " +
                std::to_string(mesh_.vertexCount()) + " vertices)");
        for (const obj::TagIndexUse& use : tagIndexUses_) {
            const bool isFace = use.kind == obj::TagIndexUse::Kind::Face;
            const int count = isFace ? mesh_.faceCount() : mesh_.vertexCount();
            if (use.index < 0 || use.index >= count)
                LineContext{path, use.line}.fail(
                    "t " + use.tag + ": " + (isFace ? "face " : "vertex ") + std::to_string(use.index) +
                    " is out of range (0-based; the file has " + std::to_string(count) +
                    (isFace ? " faces)" : " vertices)"));
        }
    }

private:
    void parseLine(std::string_view line) {
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword == "v") parseVertex(tokens);
        else if (keyword == "f") parseFace(tokens);
        else if (keyword == "t") obj::parseTagLine(line, at_, mesh_.tags, tagIndexUses_);
        // Everything else (vt, vn, comments, g, o, s, usemtl, mtllib, l, p, ...) is not geometry
        // a cage or a reference render needs.
    }

    void parseVertex(Tokens& tokens) {
        glm::vec3 p;
        for (int axis = 0; axis < 3; ++axis) {
            const std::string_view token = tokens.next();
            if (token.empty()) at_.fail("vertex has " + std::to_string(axis) + " coordinates, needs 3");
            if (!obj::parseFloat(token, p[axis])) at_.fail("bad vertex coordinate " + quoted(token));
            if (!std::isfinite(p[axis])) at_.fail("non-finite vertex coordinate " + quoted(token));
        }
        // Further numbers (w, or vertex colours some exporters append) are ignored.
        if (std::int64_t(mesh_.positions.size()) >= kMaxVertices)
            at_.fail("more than " + std::to_string(kMaxVertices) + " vertices, the most subdfit reads from one file");
        mesh_.positions.push_back(p);
    }

    void parseFace(Tokens& tokens) {
        int size = 0;
        for (std::string_view entry = tokens.next(); !entry.empty(); entry = tokens.next()) {
            mesh_.faceIndices.push_back(vertexIndex(entry));
            ++size;
        }
        if (size < 3) at_.fail("face with " + std::to_string(size) + " vertices (needs at least 3)");
        if (std::int64_t(mesh_.faceIndices.size()) > kMaxFaceCorners)
            at_.fail("more than " + std::to_string(kMaxFaceCorners) + " face corners, the most subdfit reads from one file");
        mesh_.faceSizes.push_back(size);
    }

    // The 0-based vertex of one `f` entry; only its first field (before any '/') matters.
    int vertexIndex(std::string_view entry) {
        int64_t raw = 0;
        const char* end = nullptr;
        if (!obj::parseIntPrefix(entry, raw, end) || (end != entry.data() + entry.size() && *end != '/'))
            at_.fail("bad face entry " + quoted(entry));
        if (raw == 0) at_.fail("face index 0 (OBJ indices start at 1)");
        if (raw < 0) {
            // Relative to the vertices read so far.
            const int64_t index = int64_t(mesh_.vertexCount()) + raw;
            if (index < 0)
                at_.fail("face index " + std::to_string(raw) + " points before the first vertex");
            return int(index);
        }
        if (raw > INT32_MAX) at_.fail("face index " + std::to_string(raw) + " is out of range");
        // Positive indices may legally name vertices defined further down: checked in finish().
        const int index = int(raw - 1);
        if (index > maxIndex_) {
            maxIndex_ = index;
            maxIndexLine_ = at_.line;
        }
        return index;
    }

    PolygonMesh& mesh_;
    LineContext at_;
    int maxIndex_ = -1;
    int maxIndexLine_ = 0;
    std::vector<obj::TagIndexUse> tagIndexUses_;
};

}  // namespace

PolygonMesh readObj(const std::filesystem::path& path) {
    PolygonMesh mesh;
    mesh.sourcePath = path.string();
    const std::string text = io::readInputFile(path);
    ObjParser parser(mesh);
    parser.parse(text);
    parser.finish();
    return mesh;
}

}  // namespace subdfit::mesh
