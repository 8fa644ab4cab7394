#pragma once
// Outputs appear whole or not at all: write to a temporary name in the same folder, then rename
// (atomic on POSIX). A failed write removes the temporary and rethrows.
#include <filesystem>
#include <functional>
#include <string>

namespace subdfit::io {

void writeAtomically(const std::filesystem::path& destination,
                     const std::function<void(const std::filesystem::path& temporary)>& write);

void writeTextAtomically(const std::filesystem::path& destination, const std::string& text);

}  // namespace subdfit::io
