#include "io/asset_folder.h"

#include "io/input_file.h"
#include "util/error.h"

namespace subdfit::io {

namespace fs = std::filesystem;

namespace {

bool isInside(const fs::path& path, const fs::path& folder) {
    auto p = path.begin();
    for (auto f = folder.begin(); f != folder.end(); ++f, ++p)
        if (p == path.end() || *p != *f) return false;
    return p != path.end();
}

}  // namespace

AssetFolder::AssetFolder(const fs::path& assetFile, std::string kind) : kind_(std::move(kind)) {
    std::error_code ec;
    const fs::path parent = assetFile.has_parent_path() ? assetFile.parent_path() : fs::path(".");
    folder_ = fs::canonical(parent, ec);
    if (ec) throw fileError(assetFile.string(), "cannot resolve its folder: " + ec.message());
}

bool AssetFolder::containsLexically(const fs::path& path) const { return isInside(path.lexically_normal(), folder_); }

AssetFolder::Resolved AssetFolder::resolve(const fs::path& path) const {
    Resolved out;
    std::error_code ec;
    out.file = fs::weakly_canonical(path.lexically_normal(), ec);
    if (ec) {
        out.problem = "cannot be resolved: " + ec.message();
    } else if (!fs::exists(fs::symlink_status(out.file, ec))) {
        out.missing = true;
    } else if (fs::is_symlink(fs::symlink_status(out.file, ec))) {
        out.missing = true;  // a symlink left after resolving points at nothing
    } else if (!isInside(out.file, folder_)) {
        out.problem = "resolves outside the " + kind_ + " file's folder";
    } else {
        out.problem = inputFileProblem(out.file);
    }
    return out;
}

}  // namespace subdfit::io
