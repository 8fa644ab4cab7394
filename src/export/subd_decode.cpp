#include "export/subd_decode.h"

#include <algorithm>
#include <cmath>

#include "export/surface_glb.h"
#include "util/error.h"

namespace subdfit::exporter {

int defaultDecodeSegments(const SubdAsset& asset) { return asset.maps.layout.resolution > 0 ? asset.maps.layout.resolution : 8; }

std::uint64_t decodedTriangles(const SubdAsset& asset, int segments) {
    const auto& cage = asset.cage;
    std::vector<bool> hole(size_t(cage.faceCount()), false);
    for (int face : cage.tags.holes)
        if (face >= 0 && face < cage.faceCount()) hole[size_t(face)] = true;
    std::uint64_t ptexFaces = 0;  // a quad has one, an n-gon n (Far::PtexIndices); holes none
    for (int f = 0; f < cage.faceCount(); ++f)
        if (!hole[size_t(f)]) ptexFaces += cage.faceSizes[size_t(f)] == 4 ? 1 : std::uint64_t(cage.faceSizes[size_t(f)]);
    return ptexFaces * 2 * std::uint64_t(segments) * std::uint64_t(segments);
}

int decodeSegments(const SubdAsset& asset, const DecodeDensity& density, const std::string& name) {
    int segments = density.segments;
    if (segments == 0 && density.triangles > 0) {
        const std::uint64_t perSegment = decodedTriangles(asset, 1);
        const double exact = std::sqrt(double(density.triangles) / double(std::max<std::uint64_t>(perSegment, 1)));
        segments = int(std::clamp(std::lround(exact), 1l, 64l));
    }
    if (segments == 0) segments = defaultDecodeSegments(asset);
    if (segments < 1 || segments > 64) throw Error("invalid option: --tess: must be in 1..64, got " + std::to_string(segments));
    const std::uint64_t triangles = decodedTriangles(asset, segments);
    if (triangles > kMaxDecodeTriangles)
        throw Error(name + ": " + std::to_string(segments) + " segments per face edge give " + std::to_string(triangles) +
                    " triangles, more than decode writes (" + std::to_string(kMaxDecodeTriangles) + ")");
    return segments;
}

WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out, const DecodeDensity& density) {
    const SubdAsset asset = readSubd(subd);
    return writeSurfaceGlb(out, asset.cage, asset.maps, decodeSegments(asset, density, subd.string()), false);
}

}  // namespace subdfit::exporter
