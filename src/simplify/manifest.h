#pragma once
// A batch manifest, read: one asset a line, `REFERENCE [options]`, '#' comments and blank lines
// skipped, "double" or 'single' quotes around an argument that holds spaces. The options are
// left as words for the caller's option parser (the command line's, in apps/).
//
//   # assets.txt
//   props/crate.glb --faces 200
//   "scans/statue 01.obj" --faces 2000 --map-res 8
#include <filesystem>
#include <string>
#include <vector>

namespace subdfit::simplify {

struct ManifestLine {
    int number = 0;                     // 1-based
    std::filesystem::path reference{};  // as written
    std::filesystem::path resolved{};   // relative ones from the manifest's folder
    std::vector<std::string> options{};
};

// The manifest is read as any input (a regular file, at most 64 MiB). Throws subdfit::Error
// "MANIFEST:LINE: problem" (an unterminated quote, a control character) or "MANIFEST: problem"
// (unreadable, no asset).
std::vector<ManifestLine> readManifest(const std::filesystem::path& manifest);

// One line split into words; throws subdfit::Error (without a location) for a bad line.
std::vector<std::string> splitManifestLine(const std::string& line);

}  // namespace subdfit::simplify
