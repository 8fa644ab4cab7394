#include "mesh/obj_materials.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "io/image_io.h"
#include "io/input_file.h"
#include "mesh/obj_tokens.h"
#include "util/error.h"
#include "util/warnings.h"

namespace subdfit::mesh::obj {
namespace {

namespace fs = std::filesystem;

// A file an OBJ or MTL names: relative, inside the OBJ's folder (as glTF URIs are confined).
fs::path confined(const fs::path& folder, std::string_view name, const LineContext& at) {
    const fs::path relative = fs::path(std::string(name)).lexically_normal();
    if (relative.is_absolute() || relative.empty() || *relative.begin() == "..")
        at.fail("'" + std::string(name) + "' lies outside the OBJ file's folder");
    return folder / relative;
}

class MtlParser {
public:
    MtlParser(MaterialLibrary& library, fs::path folder) : library_(library), folder_(std::move(folder)) {}

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
        std::string list;
        for (const auto& what : ignored_) list += (list.empty() ? "" : ", ") + what;
        warn(path_ + ": MTL statements not reproduced (the look may differ): " + list);
    }

private:
    void parseLine(std::string_view line, const LineContext& at) {
        Tokens tokens(line);
        const std::string_view keyword = tokens.next();
        if (keyword.empty() || keyword.front() == '#') return;
        if (keyword == "newmtl") {
            library_.names.emplace_back(restOfLine(line, keyword));
            Material m = defaultMaterial();
            m.name = library_.names.back();
            m.metallicFactor = 0.0f;
            library_.set.materials.push_back(m);
            return;
        }
        if (library_.set.materials.empty()) at.fail("'" + std::string(keyword) + "' before any newmtl");
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
        try {
            io::DecodedImage decoded = io::readImage(file);
            library_.set.images.push_back({std::string(name), decoded.width, decoded.height, std::move(decoded.rgba)});
            return int(library_.set.images.size()) - 1;
        } catch (const Error& e) {
            if (fs::exists(file)) throw;
            warn(path_ + ": line " + std::to_string(at.line) + ": texture '" + std::string(name) +
                 "' is missing; the material renders without it");
            return -1;
        }
    }

    MaterialLibrary& library_;
    fs::path folder_;
    std::string path_;
    std::set<std::string> ignored_;
};

}  // namespace

int MaterialLibrary::find(const std::string& name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : int(it - names.begin());
}

MaterialLibrary readMaterialLibraries(const fs::path& objPath, const std::vector<LibraryUse>& libraries) {
    MaterialLibrary library;
    const fs::path folder = objPath.parent_path();
    const std::string objName = objPath.string();
    for (const auto& [name, line] : libraries) {
        const fs::path file = confined(folder, name, LineContext{objName, line});
        if (!fs::exists(file)) {
            warn(objName + ": line " + std::to_string(line) + ": material library '" + name +
                 "' is missing; its materials render grey");
            continue;
        }
        MtlParser parser(library, folder);
        parser.parse(file);
        parser.finish();
    }
    return library;
}

}  // namespace subdfit::mesh::obj
