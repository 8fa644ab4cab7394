#pragma once
// The side-by-side a reviewer looks at first: one held-out view of the reference and of each
// candidate in a row, and under each candidate its error heat map against the reference.
#include <filesystem>
#include <vector>

#include <glm/vec4.hpp>

namespace subdfit::simplify {

// Images are res × res, rows bottom-up as GL reads them. Heat: per-pixel RGB RMS error,
// black (0) through red and yellow to white (≥ 0.25). Written atomically.
void writeComparison(const std::filesystem::path& path, int res, const std::vector<glm::vec4>& reference,
                     const std::vector<const std::vector<glm::vec4>*>& candidates);

}  // namespace subdfit::simplify
