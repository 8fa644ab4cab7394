#include "mesh/obj_reader.h"

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <map>

#include "io/input_file.h"
#include "mesh/input_limits.h"
#include "mesh/mesh_geometry.h"
#include "mesh/obj_materials.h"
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
    ObjParser(PolygonMesh& mesh, bool appearance) : mesh_(mesh), at_{mesh.sourcePath, 0}, appearance_(appearance) {}

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
        if (appearance_) finishAppearance();
    }

private:
    void parseLine(std::string_view line) {
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword == "v") parseVertex(tokens);
        else if (keyword == "f") parseFace(tokens);
        else if (keyword == "t") obj::parseTagLine(line, at_, mesh_.tags, tagIndexUses_);
        else if (appearance_ && keyword == "vt") parseTexCoord(tokens);
        else if (appearance_ && keyword == "usemtl") material_ = materialNamed(std::string(obj::restOfLine(line, keyword)));
        else if (appearance_ && keyword == "mtllib") libraries_.push_back({std::string(obj::restOfLine(line, keyword)), at_.line});
        // Everything else (vn, comments, g, o, s, l, p, ...) is not what a cage or a reference
        // render needs.
    }

    void parseTexCoord(Tokens& tokens) {
        glm::vec2 t(0.0f);
        for (int axis = 0; axis < 2; ++axis) {
            const std::string_view token = tokens.next();
            if (token.empty() && axis == 1) break;  // "vt u" alone: v = 0
            if (!obj::parseFloat(token, t[axis]) || !std::isfinite(t[axis])) at_.fail("bad texture coordinate " + quoted(token));
        }
        // OBJ's v grows upwards from the image's bottom row; glTF's (and ours) downwards from its top.
        texCoords_.push_back({t.x, 1.0f - t.y});
    }

    int materialNamed(const std::string& name) {
        const auto it = std::find(materialNames_.begin(), materialNames_.end(), name);
        if (it != materialNames_.end()) return int(it - materialNames_.begin());
        materialNames_.push_back(name);
        return int(materialNames_.size()) - 1;
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
            if (appearance_) cornerTexCoords_.push_back(texCoordIndex(entry));
            ++size;
        }
        if (appearance_) faceMaterialNames_.push_back(material_);
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

    // The vt of an `f` entry "v/vt[/vn]", 0-based, or -1 when it has none.
    int texCoordIndex(std::string_view entry) {
        const size_t slash = entry.find('/');
        if (slash == std::string_view::npos || slash + 1 >= entry.size() || entry[slash + 1] == '/') return -1;
        std::string_view field = entry.substr(slash + 1);
        field = field.substr(0, field.find('/'));
        int64_t raw = 0;
        if (!obj::parseInt(field, raw) || raw == 0) at_.fail("bad texture coordinate index in " + quoted(entry));
        const int64_t index = raw < 0 ? int64_t(texCoords_.size()) + raw : raw - 1;
        if (index < 0 || index >= int64_t(texCoords_.size()))
            at_.fail("texture coordinate index " + std::to_string(raw) + " is out of range (" +
                     std::to_string(texCoords_.size()) + " read so far)");
        return int(index);
    }

    // One vertex per distinct (position, texture coordinate) pair, as a renderer needs them,
    // each shaded with its position's smooth normal (the split is the texture's, not a hard
    // edge; `vn` is not read); the tags, which name the file's vertices, no longer apply and
    // are dropped.
    void finishAppearance() {
        const obj::MaterialLibrary library = obj::readMaterialLibraries(mesh_.sourcePath, libraries_);
        if (!texCoords_.empty()) {
            const std::vector<glm::vec3> smooth = vertexNormals(mesh_);
            std::vector<glm::vec3> positions;
            std::map<std::pair<int, int>, int> split;
            for (size_t k = 0; k < mesh_.faceIndices.size(); ++k) {
                const std::pair<int, int> key{mesh_.faceIndices[k], cornerTexCoords_[k]};
                const auto [it, fresh] = split.try_emplace(key, int(positions.size()));
                if (fresh) {
                    positions.push_back(mesh_.positions[size_t(key.first)]);
                    mesh_.normals.push_back(smooth[size_t(key.first)]);
                    mesh_.uvs.push_back(key.second >= 0 ? texCoords_[size_t(key.second)] : glm::vec2(0.0f));
                }
                mesh_.faceIndices[k] = it->second;
            }
            mesh_.positions = std::move(positions);
            mesh_.tags = {};
        }
        if (library.set.materials.empty()) return;
        auto set = std::make_shared<MaterialSet>(library.set);
        int grey = -1;
        for (int name : faceMaterialNames_) {
            int m = name >= 0 ? library.find(materialNames_[size_t(name)]) : -1;
            if (m < 0) {
                if (grey < 0) {
                    grey = int(set->materials.size());
                    Material plain = defaultMaterial();
                    plain.metallicFactor = 0.0f;
                    set->materials.push_back(plain);
                }
                m = grey;
            }
            mesh_.faceMaterials.push_back(m);
        }
        mesh_.materials = std::move(set);
    }

    PolygonMesh& mesh_;
    LineContext at_;
    bool appearance_;
    std::vector<glm::vec2> texCoords_;
    std::vector<int> cornerTexCoords_;     // per face corner, with appearance
    std::vector<int> faceMaterialNames_;   // per face: into materialNames_, -1 before any usemtl
    std::vector<std::string> materialNames_;
    std::vector<obj::LibraryUse> libraries_;
    int material_ = -1;
    int maxIndex_ = -1;
    int maxIndexLine_ = 0;
    std::vector<obj::TagIndexUse> tagIndexUses_;
};

}  // namespace

PolygonMesh readObj(const std::filesystem::path& path, MeshContent content) {
    PolygonMesh mesh;
    mesh.sourcePath = path.string();
    const std::string text = io::readInputFile(path);
    ObjParser parser(mesh, content == MeshContent::WithAppearance);
    parser.parse(text);
    parser.finish();
    return mesh;
}

}  // namespace subdfit::mesh
