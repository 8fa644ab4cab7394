#pragma once
// The only way tinygltf may touch the filesystem while it loads one glTF: reads of regular
// files inside the glTF's own folder (symlinks resolved), within the input size limit. Writes
// are refused, and tinygltf's fallback to the current directory never finds anything. The
// preflight (gltf_preflight.h) has refused escaping URIs by their text already; this is the
// second line, for what text cannot show (a symlink pointing out, a FIFO, a device).
#include <tiny_gltf.h>

#include <filesystem>
#include <string>

#include "io/asset_folder.h"

namespace subdfit::mesh::gltf {

class FileAccess {
public:
    explicit FileAccess(const std::filesystem::path& gltfPath);
    FileAccess(const FileAccess&) = delete;
    FileAccess& operator=(const FileAccess&) = delete;

    // Callbacks bound to this object, which must outlive the load.
    tinygltf::FsCallbacks callbacks();
    // The base folder to hand tinygltf: absolute, so that its joined paths are recognisable.
    const std::string& baseDir() const { return baseDir_; }
    // Why the first refused file was refused ("" if none was): tinygltf's own message for a
    // refused file would only say "not found".
    const std::string& refusal() const { return refusal_; }

private:
    // The file to read for tinygltf's joined path (dot segments removed, as URIs resolve them,
    // and symlinks followed), or "" when it may not be read.
    std::string resolve(const std::string& joinedPath);

    io::AssetFolder folder_;
    std::string baseDir_;
    std::string refusal_;
};

}  // namespace subdfit::mesh::gltf
