#pragma once
// Every exported file goes through io::writeAtomically (a temporary of its own beside it,
// fsynced, then a rename), and every failure surfaces as subdfit::Error "path: problem"; the
// result says how many bytes were written.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>

namespace subdfit::io {

struct WrittenFile {
    std::filesystem::path path;
    std::uintmax_t bytes = 0;
};

// `write` fills the temporary it is given (whose extension is the destination's).
WrittenFile writeOutput(const std::filesystem::path& destination,
                        const std::function<void(const std::filesystem::path& temporary)>& write);

WrittenFile writeBytes(const std::filesystem::path& destination, std::span<const unsigned char> bytes);

}  // namespace subdfit::io
