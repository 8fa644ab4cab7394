#include "io/output_folder.h"

#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "util/error.h"

namespace subdfit::io {

namespace fs = std::filesystem;

namespace {

fs::path absoluteNormal(const fs::path& path) { return fs::absolute(path).lexically_normal(); }

}  // namespace

void checkOutputFolder(const fs::path& dir, const OutputFolderRule& rule) {
    const std::string name = dir.string();
    if (dir.empty()) throw OptionError("out", "is empty");
    std::error_code ec;
    const fs::path absolute = absoluteNormal(dir);
    const fs::path resolved = fs::weakly_canonical(absolute, ec);
    if (absolute == absolute.root_path() || (!ec && resolved == resolved.root_path()))
        throw fileError(name, "is the filesystem root; choose a folder of its own");

    const fs::file_status status = fs::status(dir, ec);
    if (fs::exists(status) && !fs::is_directory(status)) throw fileError(name, "exists and is not a folder");
    if (fs::is_directory(status)) {
        bool empty = fs::is_empty(dir, ec);
        if (ec) throw fileError(name, "cannot list the folder: " + ec.message());
        bool ours = false;
        for (const std::string& marker : rule.ownMarkers) ours = ours || fs::exists(dir / marker, ec);
        if (!empty && !ours && !rule.force)
            throw fileError(name,
                            "is a folder with other files in it and no subdfit results; choose an empty or new "
                            "folder, or add --force to write into it");
    }

    // Writable: the folder itself, or the nearest existing folder it would be created in.
    fs::path existing = absolute;
    while (!fs::exists(existing, ec) && existing.has_relative_path()) existing = existing.parent_path();
    if (!fs::is_directory(existing, ec))
        throw fileError(name, "cannot be created: '" + existing.string() + "' is not a folder");
    if (access(existing.c_str(), W_OK | X_OK) != 0)
        throw fileError(name, (existing == absolute ? std::string("cannot be written: ")
                                                    : "cannot be created in '" + existing.string() + "': ") +
                                  std::strerror(errno));
}

bool isStrictlyInside(const fs::path& path, const fs::path& folder) {
    const fs::path p = absoluteNormal(path), f = absoluteNormal(folder);
    auto pi = p.begin();
    for (auto fi = f.begin(); fi != f.end(); ++fi, ++pi) {
        if (fi->empty() && std::next(fi) == f.end()) break;  // a trailing separator
        if (pi == p.end() || *pi != *fi) return false;
    }
    return pi != p.end() && !pi->empty();
}

}  // namespace subdfit::io
