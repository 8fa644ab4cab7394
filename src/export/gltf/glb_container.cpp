#include "export/gltf/glb_container.h"

#include <cstdint>
#include <limits>
#include <string>

#include "util/error.h"
#include "util/json_text.h"

namespace subdfit::exporter {
namespace {

constexpr std::uint32_t kMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kVersion = 2;
constexpr std::uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kBinChunk = 0x004E4942;   // "BIN\0"

size_t padded(size_t size) { return (size + 3) & ~size_t(3); }

void appendU32(std::vector<unsigned char>& out, std::uint32_t value) {
    for (int shift = 0; shift < 32; shift += 8)
        out.push_back((unsigned char)((value >> shift) & 0xFF));  // little-endian
}

void appendChunk(std::vector<unsigned char>& out, std::uint32_t type, std::span<const unsigned char> data,
                 unsigned char pad) {
    appendU32(out, std::uint32_t(padded(data.size())));
    appendU32(out, type);
    out.insert(out.end(), data.begin(), data.end());
    out.resize(out.size() + padded(data.size()) - data.size(), pad);
}

}  // namespace

std::vector<unsigned char> packGlb(const nlohmann::json& document, std::span<const unsigned char> binary) {
    const std::string json = jsonText(document);
    const size_t total = 12 + 8 + padded(json.size()) + (binary.empty() ? 0 : 8 + padded(binary.size()));
    if (total > std::numeric_limits<std::uint32_t>::max())
        throw Error("the GLB would be " + std::to_string(total) + " bytes, beyond the format's 4 GiB limit");
    std::vector<unsigned char> out;
    out.reserve(total);
    appendU32(out, kMagic);
    appendU32(out, kVersion);
    appendU32(out, std::uint32_t(total));
    // JSON must be padded with spaces (0x20) so that it stays valid JSON; BIN with zeros.
    appendChunk(out, kJsonChunk, {reinterpret_cast<const unsigned char*>(json.data()), json.size()}, ' ');
    if (!binary.empty()) appendChunk(out, kBinChunk, binary, 0);
    return out;
}

}  // namespace subdfit::exporter
