#pragma once
// A batch manifest as batch items: the core reads the lines (simplify/manifest.h), each line's
// options are parsed here by the same CLI11 rules as `subdfit simplify`'s.
#include <filesystem>
#include <vector>

#include "simplify/batch.h"

namespace subdfit::apps {

// `defaults` are the batch's own options; a line's options override them. Throws
// subdfit::Error "manifest:line: problem". Repeated assets are dropped with a line to `log`.
std::vector<simplify::BatchItem> readManifest(const std::filesystem::path& manifest,
                                              const simplify::SimplifyOptions& defaults, const simplify::BatchLog& log);

}  // namespace subdfit::apps
