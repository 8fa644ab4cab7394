#pragma once
// The side-by-side a reviewer looks at first: one held-out view of the reference and of each
// candidate in a row, each labelled with its name, bytes and PSNR, and under each candidate its
// error heat map against the reference (the scale under the reference).
#include <filesystem>
#include <string>
#include <vector>

#include "simplify/compare/quality.h"

namespace subdfit::simplify {

// One candidate's column: its name ("subdfit", "decimation + Draco", ...) and its quality
// (bytes, held-out PSNR, held-out view 0 as rendered).
struct ComparisonColumn {
    std::string name;
    const Quality* quality = nullptr;
};

// Views are res × res, rows bottom-up as GL reads them. Heat: per-pixel RGB RMS error, black
// (0) through red and yellow to white (≥ 0.25). Written atomically.
void writeComparison(const std::filesystem::path& path, int res, const std::vector<glm::vec4>& reference,
                     const std::vector<ComparisonColumn>& columns);

}  // namespace subdfit::simplify
