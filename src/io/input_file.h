#pragma once
// Reading files that someone else made. Only regular files are opened (a FIFO would block
// forever, /dev/zero never ends), checked on the open descriptor so that a swapped symlink
// cannot slip past; at most kMaxInputBytes are read; a stop request (util/interrupt.h) is
// noticed between chunks.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace subdfit::io {

// 2 GiB: a 30-million-triangle OBJ; glTF cannot address more than 4 GiB anyway.
inline constexpr std::uint64_t kMaxInputBytes = std::uint64_t(2) << 30;

// The whole file. Throws subdfit::Error "path: problem" when it is missing, a folder, not a
// regular file, larger than maxBytes or unreadable.
std::string readInputFile(const std::filesystem::path& path, std::uint64_t maxBytes = kMaxInputBytes);

// The same checks and reads, chunk by chunk, without holding the file in memory.
void readInputFile(const std::filesystem::path& path, const std::function<void(std::string_view chunk)>& consume,
                   std::uint64_t maxBytes = kMaxInputBytes);

// Why `path` may not be read ("" when it may): missing, a folder, not a regular file, too big.
// For callers that must decide before reading (tinygltf's file-exists callback).
std::string inputFileProblem(const std::filesystem::path& path, std::uint64_t maxBytes = kMaxInputBytes);

// 32 hex digits of XXH3-128 over the file's bytes (read as above): an input's identity.
std::string fileDigest(const std::filesystem::path& path);

}  // namespace subdfit::io
