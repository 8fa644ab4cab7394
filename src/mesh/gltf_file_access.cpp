#include "mesh/gltf_file_access.h"

#include "io/input_file.h"
#include "util/error.h"

namespace subdfit::mesh::gltf {

namespace {

namespace fs = std::filesystem;

bool isInside(const fs::path& path, const fs::path& folder) {
    auto p = path.begin();
    for (auto f = folder.begin(); f != folder.end(); ++f, ++p)
        if (p == path.end() || *p != *f) return false;
    return p != path.end();
}

FileAccess& self(void* userData) { return *static_cast<FileAccess*>(userData); }

}  // namespace

FileAccess::FileAccess(const fs::path& gltfPath) {
    std::error_code ec;
    const fs::path parent = gltfPath.has_parent_path() ? gltfPath.parent_path() : fs::path(".");
    folder_ = fs::canonical(parent, ec);
    if (ec) throw fileError(gltfPath.string(), "cannot resolve its folder: " + ec.message());
    baseDir_ = folder_.string();
}

std::string FileAccess::resolve(const std::string& joinedPath) {
    // tinygltf tries baseDir/uri, then ./uri: only the first is ours to allow.
    const fs::path path = fs::path(joinedPath).lexically_normal();
    if (!isInside(path, folder_)) return "";
    std::error_code ec;
    const fs::path resolved = fs::weakly_canonical(path, ec);
    // A missing file is tinygltf's to report ("File not found"), and only a buffer must exist.
    if (!ec && !fs::exists(fs::symlink_status(resolved, ec))) return "";
    std::string problem;
    if (ec) problem = "cannot be resolved: " + ec.message();
    else if (!isInside(resolved, folder_)) problem = "resolves outside the glTF file's folder";
    else problem = io::inputFileProblem(resolved);
    if (problem.empty()) return resolved.string();
    if (refusal_.empty()) refusal_ = "external file '" + path.lexically_relative(folder_).string() + "' " + problem;
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
            io::readInputFile(file, [&](std::string_view chunk) { out->insert(out->end(), chunk.begin(), chunk.end()); });
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
