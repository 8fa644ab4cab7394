#include "gl/shader_sources.h"

#include <opensubdiv/osd/glslPatchShaderSource.h>

#include <set>
#include <sstream>

#include "util/error.h"

namespace subdfit::gl {
namespace {

// The core's shaders and whatever the running app added (static initialisers may add before
// main, so the registry is built on first use).
std::map<std::string, std::string>& registry() {
    static std::map<std::string, std::string> sources = embeddedShaderSources();
    return sources;
}

std::string rawSource(const std::string& name) {
    if (name == "osd_patch_basis")
        return "#define OSD_PATCH_BASIS_GLSL\n" + OpenSubdiv::Osd::GLSLPatchShaderSource::GetPatchBasisShaderSource();
    const auto& sources = registry();
    auto it = sources.find(name);
    if (it == sources.end()) throw Error("shader '" + name + "' is not in glsl/ nor among this program's own");
    return it->second;
}

void expandInto(const std::string& name, std::set<std::string>& seen, std::string& out) {
    if (!seen.insert(name).second) return;
    std::istringstream lines(rawSource(name));
    for (std::string line; std::getline(lines, line);) {
        const auto pos = line.find("#include \"");
        if (pos != std::string::npos && line.find_first_not_of(" \t") == pos) {
            const auto begin = pos + 10;
            expandInto(line.substr(begin, line.find('"', begin) - begin), seen, out);
        } else {
            out += line;
            out += '\n';
        }
    }
}

}  // namespace

bool addShaderSources(const std::map<std::string, std::string>& sources) {
    for (const auto& [name, text] : sources) SUBDFIT_CHECK(registry().emplace(name, text).second);  // names are unique
    return true;
}

std::string expandedShaderSource(const std::string& name) {
    std::set<std::string> seen;
    std::string out;
    expandInto(name, seen, out);
    return out;
}

}  // namespace subdfit::gl
