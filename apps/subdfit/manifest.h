#pragma once
// A batch manifest: one asset a line, `REFERENCE [simplify options]` (quotes allowed), `#`
// comments and blank lines skipped, relative paths taken from the manifest's folder.
//
//   # assets.txt
//   props/crate.glb --faces 200
//   "scans/statue 01.obj" --faces 2000 --map-res 8
#include <filesystem>
#include <vector>

#include "simplify/batch.h"

namespace subdfit::apps {

// `defaults` are the batch's own options; a line's options override them. Throws
// subdfit::Error "manifest:line: problem".
std::vector<simplify::BatchItem> readManifest(const std::filesystem::path& manifest,
                                              const simplify::SimplifyOptions& defaults);

}  // namespace subdfit::apps
