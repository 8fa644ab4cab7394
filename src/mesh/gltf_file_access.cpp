#include "mesh/gltf_file_access.h"

#include "io/input_file.h"
#include "util/error.h"

namespace subdfit::mesh::gltf {

namespace {

FileAccess& self(void* userData) { return *static_cast<FileAccess*>(userData); }

}  // namespace

FileAccess::FileAccess(const std::filesystem::path& gltfPath)
    : folder_(gltfPath, "glTF"), baseDir_(folder_.path().string()) {}

std::string FileAccess::resolve(const std::string& joinedPath) {
    // tinygltf tries baseDir/uri, then ./uri: only the first is ours to allow.
    const std::filesystem::path path = std::filesystem::path(joinedPath).lexically_normal();
    if (!folder_.containsLexically(path)) return "";
    const io::AssetFolder::Resolved resolved = folder_.resolve(path);
    // A missing file is tinygltf's to report ("File not found"), and only a buffer must exist.
    if (resolved.missing) return "";
    if (resolved.problem.empty()) return resolved.file.string();
    if (refusal_.empty())
        refusal_ = "external file '" + path.lexically_relative(folder_.path()).string() + "' " + resolved.problem;
    return "";
}

tinygltf::FsCallbacks FileAccess::callbacks() {
    tinygltf::FsCallbacks fs{};
    fs.user_data = this;
    fs.ExpandFilePath = [](const std::string& path, void*) { return path; };  // no ~ or $VAR expansion
    fs.FileExists = [](const std::string& path, void* user) { return !self(user).resolve(path).empty(); };
    fs.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
        const std::string file = self(user).resolve(path);
        if (file.empty()) {
            if (err) *err += self(user).refusal();
            return false;
        }
        try {
            out->clear();
            io::readInputFile(file,
                              [&](std::string_view chunk) { out->insert(out->end(), chunk.begin(), chunk.end()); });
            return true;
        } catch (const Error& e) {
            if (err) *err += e.what();
            return false;
        }
    };
    fs.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
        if (err) *err += "subdfit never writes through the glTF loader";
        return false;
    };
    return fs;
}

}  // namespace subdfit::mesh::gltf
