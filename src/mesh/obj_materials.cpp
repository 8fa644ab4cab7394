#include "mesh/obj_materials.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "io/asset_folder.h"
#include "io/image_io.h"
#include "io/input_file.h"
#include "mesh/obj_tokens.h"
#include "util/error.h"
#include "util/printable.h"
#include "util/warnings.h"

namespace subdfit::mesh::obj {
namespace {

namespace fs = std::filesystem;

// A file an OBJ or MTL names, relative to the OBJ's folder, resolved as glTF URIs are
// (io/asset_folder.h): inside the folder once symlinks are followed, and a regular file. Empty
// when it is missing (the caller warns); a refusal names the line.
fs::path confined(const io::AssetFolder& folder, std::string_view name, const LineContext& at) {
    const fs::path relative = fs::path(std::string(name)).lexically_normal();
    if (relative.is_absolute() || relative.empty() || *relative.begin() == "..")
        at.fail("'" + printable(name) + "' lies outside the OBJ file's folder");
    const io::AssetFolder::Resolved resolved = folder.resolve(folder.path() / relative);
    if (resolved.missing) return {};
    if (!resolved.problem.empty()) at.fail("'" + printable(name) + "' " + resolved.problem);
    return resolved.file;
}

// What the libraries of one OBJ share: each map file decoded once, all within one pixel budget.
struct ImageCache {
    io::PixelBudget budget;
    std::map<fs::path, int> decoded;  // resolved file -> index into MaterialSet::images
};

class MtlParser {
public:
    MtlParser(MaterialLibrary& library, const io::AssetFolder& folder, ImageCache& images)
        : library_(library), folder_(folder), images_(images) {}

    void parse(const fs::path& file) {
        const std::string text = io::readInputFile(file);
        path_ = file.string();
        LineContext at{path_, 0};
        std::string_view rest = text;
        while (!rest.empty()) {
            ++at.line;
            const size_t eol = rest.find('\n');
            const std::string_view line = rest.substr(0, eol);
            rest.remove_prefix(eol == std::string_view::npos ? rest.size() : eol + 1);
            parseLine(line, at);
        }
    }

    void finish() const {
        if (ignored_.empty()) return;
        constexpr size_t kMostNamed = 12;  // a file of random keywords must not make a huge line
        std::string list;
        size_t named = 0;
        for (const auto& what : ignored_)
            if (named++ < kMostNamed) list += (list.empty() ? "" : ", ") + printable(what, 24);
        if (ignored_.size() > kMostNamed) list += " and " + std::to_string(ignored_.size() - kMostNamed) + " more";
        warn(path_ + ": MTL statements not reproduced (the look may differ): " + list);
    }

private:
    void parseLine(std::string_view line, const LineContext& at) {
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword.empty() || keyword.front() == '#') return;
        if (keyword == "newmtl") {
            library_.add(std::string(restOfLine(line, keyword)));
            return;
        }
        if (library_.set.materials.empty()) at.fail(quoted(keyword) + " before any newmtl");
        Material& m = library_.set.materials.back();
        if (keyword == "Kd") {
            const glm::vec3 kd = numbers<3>(tokens, at);
            m.baseColorFactor = glm::vec4(kd, m.baseColorFactor.a);
        } else if (keyword == "d") {
            m.baseColorFactor.a = numbers<1>(tokens, at).x;
        } else if (keyword == "Tr") {
            m.baseColorFactor.a = 1.0f - numbers<1>(tokens, at).x;
        } else if (keyword == "Ns") {
            const float ns = std::max(0.0f, numbers<1>(tokens, at).x);
            m.roughnessFactor = std::sqrt(2.0f / (ns + 2.0f));
        } else if (keyword == "map_Kd") {
            m.baseColorTexture.image = image(restOfLine(line, keyword), at);
        } else {
            ignored_.insert(std::string(keyword));
        }
    }

    template <int N>
    glm::vec<N, float> numbers(Tokens& tokens, const LineContext& at) {
        glm::vec<N, float> v(0.0f);
        for (int k = 0; k < N; ++k) {
            const std::string_view token = tokens.next();
            if (token.empty() && k > 0) return glm::vec<N, float>(v[0]);  // "Kd 0.5" is grey
            if (!parseFloat(token, v[k]) || !std::isfinite(v[k])) at.fail("bad number " + quoted(token));
        }
        return v;
    }

    // Map options (-s, -o, -bm, ...) are not read: the last token is the file.
    int image(std::string_view name, const LineContext& at) {
        if (name.find(" -") != std::string_view::npos || (!name.empty() && name.front() == '-')) {
            ignored_.insert("map options");
            name = name.substr(name.rfind(' ') + 1);
        }
        const fs::path file = confined(folder_, name, at);
        if (file.empty()) {
            warn(path_ + ": line " + std::to_string(at.line) + ": texture '" + printable(name) +
                 "' is missing; the material renders without it");
            return -1;
        }
        if (const auto known = images_.decoded.find(file); known != images_.decoded.end()) return known->second;
        io::DecodedImage decoded = io::readImage(file, &images_.budget);
        library_.set.images.push_back({std::string(name), decoded.width, decoded.height, std::move(decoded.rgba)});
        return images_.decoded[file] = int(library_.set.images.size()) - 1;
    }

    MaterialLibrary& library_;
    const io::AssetFolder& folder_;
    ImageCache& images_;
    std::string path_;
    std::set<std::string> ignored_;
};

}  // namespace

void MaterialLibrary::add(std::string name) {
    Material m = defaultMaterial();
    m.name = name;
    m.metallicFactor = 0.0f;
    set.materials.push_back(m);
    index_.emplace(name, int(names.size()));  // a repeated name keeps its first material
    names.push_back(std::move(name));
}

int MaterialLibrary::find(const std::string& name) const {
    const auto it = index_.find(name);
    return it == index_.end() ? -1 : it->second;
}

MaterialLibrary readMaterialLibraries(const fs::path& objPath, const std::vector<LibraryUse>& libraries) {
    MaterialLibrary library;
    const io::AssetFolder folder(objPath, "OBJ");
    const std::string objName = objPath.string();
    ImageCache images;
    for (const auto& [name, line] : libraries) {
        const fs::path file = confined(folder, name, LineContext{objName, line});
        if (file.empty()) {
            warn(objName + ": line " + std::to_string(line) + ": material library '" + printable(name) +
                 "' is missing; its materials render grey");
            continue;
        }
        MtlParser parser(library, folder, images);
        parser.parse(file);
        parser.finish();
    }
    return library;
}

}  // namespace subdfit::mesh::obj
