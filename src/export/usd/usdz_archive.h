#pragma once
// A .usdz package, as the USDZ specification has it: a zip archive whose entries are stored
// (never compressed, never encrypted), each entry's data starting at a multiple of 64 bytes from
// the start of the file so that a reader can map it in place; the first entry is the package's
// root layer. The padding is an extra field of the local header (id 0x1986, as USD's own
// writer pads). No zip64: a package is refused past 4 GiB.
#include <span>
#include <string>
#include <vector>

namespace subdfit::exporter {

struct UsdzEntry {
    std::string name;  // path inside the package, '/'-separated
    std::vector<unsigned char> bytes;
};

inline constexpr std::size_t kUsdzAlignment = 64;

// Throws subdfit::Error for no entries, an empty or repeated name, or an archive past 4 GiB.
std::vector<unsigned char> usdzArchive(std::span<const UsdzEntry> entries);

}  // namespace subdfit::exporter
