#pragma once
// The folder of an asset file (a glTF, an OBJ), and the only files the asset may make a reader
// open: those inside it once every symlink is followed, and regular ones (not a FIFO, a device,
// a folder). glTF buffers and images, OBJ material libraries and their maps all go through here,
// so that `m.mtl -> /etc/passwd`, `d/x.mtl` with `d -> /etc`, or a texture linking to
// ../outside/secret.png are refused by the same rule.
#include <filesystem>
#include <string>

namespace subdfit::io {

class AssetFolder {
public:
    // `assetFile`'s folder, resolved; `kind` names the asset in messages ("glTF", "OBJ").
    // Throws subdfit::Error naming the file when the folder cannot be resolved.
    AssetFolder(const std::filesystem::path& assetFile, std::string kind);

    const std::filesystem::path& path() const { return folder_; }  // canonical

    // Whether `path` (dot segments removed) names something inside the folder, by its text.
    bool containsLexically(const std::filesystem::path& path) const;

    struct Resolved {
        std::filesystem::path file;  // symlinks followed
        bool missing = false;        // nothing there (a dangling symlink included): the reader's to report
        std::string problem;         // why it may not be read ("" when it may)
    };
    // `path`, inside the folder by its text (containsLexically), resolved.
    Resolved resolve(const std::filesystem::path& path) const;

private:
    std::filesystem::path folder_;
    std::string kind_;
};

}  // namespace subdfit::io
