#include "mesh/obj_reader.h"

#include <cmath>
#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <unordered_map>

#include <glm/geometric.hpp>

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
            LineContext{path, maxIndexLine_}.fail("face index " + std::to_string(maxIndex_ + 1) +
                                                  " is out of range (the file has " +
                                                  std::to_string(mesh_.vertexCount()) + " vertices)");
        for (const obj::TagIndexUse& use : tagIndexUses_) {
            const bool isFace = use.kind == obj::TagIndexUse::Kind::Face;
            const int count = isFace ? mesh_.faceCount() : mesh_.vertexCount();
            if (use.index < 0 || use.index >= count)
                LineContext{path, use.line}.fail("t " + use.tag + ": " + (isFace ? "face " : "vertex ") +
                                                 std::to_string(use.index) +
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
        else if (appearance_ && keyword == "vn") parseNormal(tokens);
        else if (appearance_ && keyword == "usemtl")
            material_ = materialNamed(std::string(obj::restOfLine(line, keyword)));
        else if (appearance_ && keyword == "mtllib")
            libraries_.push_back({std::string(obj::restOfLine(line, keyword)), at_.line});
        // Everything else (comments, g, o, s, l, p, ...) is not what a cage or a reference
        // render needs.
    }

    void parseTexCoord(Tokens& tokens) {
        glm::vec2 t(0.0f);
        for (int axis = 0; axis < 2; ++axis) {
            const std::string_view token = tokens.next();
            if (token.empty() && axis == 1) break;  // "vt u" alone: v = 0
            if (!obj::parseFloat(token, t[axis]) || !std::isfinite(t[axis]))
                at_.fail("bad texture coordinate " + quoted(token));
        }
        // OBJ's v grows upwards from the image's bottom row; glTF's (and ours) downwards from its top.
        texCoords_.push_back({t.x, 1.0f - t.y});
    }

    void parseNormal(Tokens& tokens) {
        glm::vec3 n(0.0f);
        for (int axis = 0; axis < 3; ++axis) {
            const std::string_view token = tokens.next();
            if (!obj::parseFloat(token, n[axis]) || !std::isfinite(n[axis])) at_.fail("bad normal " + quoted(token));
        }
        normals_.push_back(n);
    }

    int materialNamed(std::string name) {
        const auto [it, fresh] = materialIndex_.try_emplace(std::move(name), int(materialNames_.size()));
        if (fresh) materialNames_.push_back(it->first);
        return it->second;
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
            if (appearance_) {
                cornerTexCoords_.push_back(attributeIndex(entry, 1, texCoords_.size(), "texture coordinate"));
                cornerNormals_.push_back(attributeIndex(entry, 2, normals_.size(), "normal"));
            }
            ++size;
        }
        if (appearance_) faceMaterialNames_.push_back(material_);
        if (size < 3) at_.fail("face with " + std::to_string(size) + " vertices (needs at least 3)");
        if (std::int64_t(mesh_.faceIndices.size()) > kMaxFaceCorners)
            at_.fail("more than " + std::to_string(kMaxFaceCorners) +
                     " face corners, the most subdfit reads from one file");
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
            if (index < 0) at_.fail("face index " + std::to_string(raw) + " points before the first vertex");
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

    // Field `field` (1: vt, 2: vn) of an `f` entry "v/vt/vn", 0-based into the `count` read so
    // far, or -1 when the entry has none.
    int attributeIndex(std::string_view entry, int field, size_t count, const char* what) {
        for (int k = 0; k < field; ++k) {
            const size_t slash = entry.find('/');
            if (slash == std::string_view::npos) return -1;
            entry = entry.substr(slash + 1);
        }
        entry = entry.substr(0, entry.find('/'));
        if (entry.empty()) return -1;
        int64_t raw = 0;
        if (!obj::parseInt(entry, raw) || raw == 0) at_.fail(std::string("bad ") + what + " index " + quoted(entry));
        const int64_t index = raw < 0 ? int64_t(count) + raw : raw - 1;
        if (index < 0 || index >= int64_t(count))
            at_.fail(std::string(what) + " index " + std::to_string(raw) + " is out of range (" +
                     std::to_string(count) + " read so far)");
        return int(index);
    }

    // One vertex per distinct (position, texture coordinate, normal), as a renderer needs them,
    // shaded with its `vn` or, without one (or with a zero one), its position's smooth normal: a
    // split only by texture coordinates is the texture's, not a hard edge. The tags, which name
    // the file's vertices, no longer apply and are dropped.
    void finishAppearance() {
        obj::MaterialLibrary library = obj::readMaterialLibraries(mesh_.sourcePath, libraries_);
        if (!texCoords_.empty() || !normals_.empty()) {
            const std::vector<glm::vec3> smooth = vertexNormals(mesh_);
            std::vector<glm::vec3> positions;
            std::map<std::array<int, 3>, int> split;
            for (size_t k = 0; k < mesh_.faceIndices.size(); ++k) {
                const std::array<int, 3> key{mesh_.faceIndices[k], cornerTexCoords_[k], cornerNormals_[k]};
                const auto [it, fresh] = split.try_emplace(key, int(positions.size()));
                if (fresh) {
                    const auto [v, vt, vn] = key;
                    positions.push_back(mesh_.positions[size_t(v)]);
                    const float length = vn >= 0 ? glm::length(normals_[size_t(vn)]) : 0.0f;
                    mesh_.normals.push_back(length > 0.0f ? normals_[size_t(vn)] / length : smooth[size_t(v)]);
                    if (!texCoords_.empty()) mesh_.uvs.push_back(vt >= 0 ? texCoords_[size_t(vt)] : glm::vec2(0.0f));
                }
                mesh_.faceIndices[k] = it->second;
            }
            mesh_.positions = std::move(positions);
            mesh_.tags = {};
        }
        if (library.set.materials.empty()) return;
        auto set = std::make_shared<MaterialSet>(std::move(library.set));
        std::vector<int> materialOfName;  // per usemtl name: into the library, -1 when it lacks the name
        for (const std::string& name : materialNames_) materialOfName.push_back(library.find(name));
        int grey = -1;
        for (int name : faceMaterialNames_) {
            int m = name >= 0 ? materialOfName[size_t(name)] : -1;
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
    std::vector<glm::vec3> normals_;
    std::vector<int> cornerTexCoords_, cornerNormals_;  // per face corner, with appearance
    std::vector<int> faceMaterialNames_;                // per face: into materialNames_, -1 before any usemtl
    std::vector<std::string> materialNames_;
    std::unordered_map<std::string, int> materialIndex_;  // name -> into materialNames_
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
