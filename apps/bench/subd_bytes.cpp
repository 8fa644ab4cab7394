#include "subd_bytes.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "export/subd_format.h"
#include "util/error.h"

namespace subdfit::bench {
namespace {

// Header: "SUBD", u16 version, u16 flags, u32 sections, u32 decode triangles; then per section a
// 4-byte tag, u32 stored bytes, u32 raw bytes and the stored bytes (docs/asset-subd-format.md).
std::map<std::string, std::size_t> sectionSizes(const std::vector<unsigned char>& bytes, const std::filesystem::path& file) {
    constexpr std::size_t kHeader = 16, kSectionHeader = 12;
    std::map<std::string, std::size_t> sizes;
    if (bytes.size() < kHeader) throw fileError(file, "too short for a .subd header");
    std::uint32_t count = 0;
    std::memcpy(&count, &bytes[8], 4);
    std::size_t at = kHeader;
    for (std::uint32_t s = 0; s < count; ++s) {
        if (at + kSectionHeader > bytes.size()) throw fileError(file, "truncated section table");
        std::uint32_t stored = 0;
        std::memcpy(&stored, &bytes[at + 4], 4);
        sizes[std::string(reinterpret_cast<const char*>(&bytes[at]), 4)] = kSectionHeader + stored;
        at += kSectionHeader + stored;
    }
    return sizes;
}

}  // namespace

SubdBytes subdBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), {}};
    SubdBytes out;
    out.file = bytes.size();
    out.sections = sectionSizes(bytes, file);
    const exporter::SubdAsset asset = exporter::decodeSubd(bytes, file.string());
    const mesh::PolygonMesh& cage = asset.cage;
    out.cage = exporter::cageByteParts(cage, exporter::SubdPrecision{}.positionBits);
    out.faces = cage.faceCount();
    out.vertices = cage.vertexCount();
    std::vector<int> valence(std::size_t(cage.vertexCount()), 0), nonQuads(std::size_t(cage.vertexCount()), 0);
    for (int f = 0, first = 0; f < cage.faceCount(); first += cage.faceSizes[std::size_t(f)], ++f) {
        const int n = cage.faceSizes[std::size_t(f)];
        out.quads += n == 4;
        for (int k = 0; k < n; ++k) {
            ++valence[std::size_t(cage.faceIndices[std::size_t(first + k)])];
            nonQuads[std::size_t(cage.faceIndices[std::size_t(first + k)])] += n != 4;
        }
    }
    // Four quads around a vertex: four faces, and (on a closed manifold) four edges.
    for (std::size_t v = 0; v < valence.size(); ++v) out.regularVertices += valence[v] == 4 && nonQuads[v] == 0;
    return out;
}

}  // namespace subdfit::bench
