#pragma once
// Where a run may write, decided before it reads an input: not the filesystem root, not a
// file, a folder that can be created and written, and not somebody else's non-empty folder
// (a typo in --out must not scatter results among a user's files) unless they force it.
#include <filesystem>
#include <string>
#include <vector>

namespace subdfit::io {

struct OutputFolderRule {
    // Names whose presence marks a non-empty folder as subdfit's own (a previous run's
    // report.json or checkpoint.bin, a batch's bookkeeping folder).
    std::vector<std::string> ownMarkers{};
    bool force = false;  // write into any folder (still never the root)
};

// Throws subdfit::Error "DIR: problem" when the folder may not be used. Creates nothing.
void checkOutputFolder(const std::filesystem::path& dir, const OutputFolderRule& rule);

// True when `path`, made absolute and normalised, lies strictly inside `folder`. For paths
// built from names that came from input files, checked before anything there is touched.
bool isStrictlyInside(const std::filesystem::path& path, const std::filesystem::path& folder);

}  // namespace subdfit::io
