#include "subd_bytes.h"

#include <fstream>
#include <iterator>
#include <vector>

#include "codec/subd_format.h"

namespace subdfit::bench {

SubdBytes subdBytes(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    const std::vector<unsigned char> bytes{std::istreambuf_iterator<char>(in), {}};
    const codec::ShippedSubd shipped = codec::readShippedSubd(bytes, file.string());
    SubdBytes out;
    out.file = bytes.size();
    out.sections.insert(shipped.sectionBytes.begin(), shipped.sectionBytes.end());
    const mesh::PolygonMesh& cage = shipped.asset.cage;
    out.cage = codec::cageByteParts(cage, shipped.positionBits);
    out.faces = cage.faceCount();
    out.vertices = cage.vertexCount();
    out.positionBits = shipped.positionBits;
    std::vector<int> valence(std::size_t(cage.vertexCount()), 0), nonQuads(std::size_t(cage.vertexCount()), 0);
    for (int f = 0, first = 0; f < cage.faceCount(); first += cage.faceSizes[std::size_t(f)], ++f) {
        const int n = cage.faceSizes[std::size_t(f)];
        out.quads += n == 4;
        for (int k = 0; k < n; ++k) {
            ++valence[std::size_t(cage.faceIndices[std::size_t(first + k)])];
            nonQuads[std::size_t(cage.faceIndices[std::size_t(first + k)])] += n != 4;
        }
    }
    for (std::size_t v = 0; v < valence.size(); ++v) out.regularVertices += valence[v] == 4 && nonQuads[v] == 0;
    return out;
}

}  // namespace subdfit::bench
