#include "codec/decode_density.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "util/error.h"

namespace subdfit::codec {

std::int64_t surfacePtexFaces(const mesh::PolygonMesh& cage) {
    const std::unordered_set<int> holes(cage.tags.holes.begin(), cage.tags.holes.end());
    std::int64_t faces = 0;
    for (int f = 0; f < cage.faceCount(); ++f)
        if (!holes.count(f)) faces += cage.faceSizes[size_t(f)] == 4 ? 1 : cage.faceSizes[size_t(f)];
    return faces;
}

DecodeDensity densityAt(const mesh::PolygonMesh& cage, int segments) {
    const std::int64_t faces = surfacePtexFaces(cage), s = segments;
    return {.segments = segments, .triangles = 2 * s * s * faces, .vertices = (s + 1) * (s + 1) * faces};
}

DecodeDensity decodeDensity(const SubdAsset& asset, const DensityRequest& request, const std::string& name) {
    return decodeDensity(
        {.cage = asset.cage, .decodeTriangles = asset.decodeTriangles, .mapResolution = asset.maps.layout.resolution},
        request, name);
}

DecodeDensity decodeDensity(const SubdOutline& asset, const DensityRequest& request, const std::string& name) {
    if (request.segments < 0 || request.triangles < 0)
        throw OptionError(request.segments < 0 ? "tess" : "triangles", "must be positive");
    if (request.segments > 0 && request.triangles > 0)
        throw OptionError("tess", "and --triangles ask for the same thing: give one");
    if (request.segments > kMaxDecodeSegments)
        throw OptionError("tess", "must be in 1.." + std::to_string(kMaxDecodeSegments) + ", got " +
                                      std::to_string(request.segments));
    const std::int64_t faces = std::max<std::int64_t>(surfacePtexFaces(asset.cage), 1);
    auto refuse = [&](const DecodeDensity& d, const std::string& asked) {
        throw Error(name + ": " + asked + " make " + std::to_string(d.triangles) + " triangles, more than the " +
                    std::to_string(kMaxDecodeTriangles) + " subdfit decodes");
    };
    if (request.segments > 0) {
        const DecodeDensity d = densityAt(asset.cage, request.segments);
        if (d.triangles > kMaxDecodeTriangles) refuse(d, std::to_string(request.segments) + " segments a face edge");
        return d;
    }
    if (request.triangles > kMaxDecodeTriangles)
        throw Error(name + ": " + std::to_string(request.triangles) + " triangles asked for, more than the " +
                    std::to_string(kMaxDecodeTriangles) + " subdfit decodes");
    const std::int64_t target = request.triangles > 0 ? request.triangles : std::int64_t(asset.decodeTriangles);
    if (target == 0) {
        // No count recorded: the maps' density (8 without), the most segments within the fallback.
        int segments = std::clamp(asset.mapResolution > 0 ? asset.mapResolution : 8, 1, kMaxDecodeSegments);
        while (segments > 1 && densityAt(asset.cage, segments).triangles > kFallbackTriangles) --segments;
        const DecodeDensity d = densityAt(asset.cage, segments);
        if (d.triangles > kMaxDecodeTriangles) refuse(d, "its faces at one segment each");
        return d;
    }
    // The whole number of segments nearest in ratio (so the count is within 2x of the target);
    // at least one, whatever the target (the cage itself).
    const double exact = std::sqrt(double(std::min(target, kMaxDecodeTriangles)) / double(2 * faces));
    const double below = std::max(1.0, std::floor(exact));
    int segments =
        std::clamp(int(exact < std::sqrt(below * (below + 1.0)) ? below : below + 1.0), 1, kMaxDecodeSegments);
    while (segments > 1 && densityAt(asset.cage, segments).triangles > kMaxDecodeTriangles) --segments;
    const DecodeDensity d = densityAt(asset.cage, segments);
    if (d.triangles > kMaxDecodeTriangles) refuse(d, "its faces at one segment each");
    return d;
}

std::uint64_t decodeOutputBytes(const DecodeDensity& d) {
    return std::uint64_t(d.vertices) * DecodeCost::kOutputVertex +
           std::uint64_t(d.triangles) * DecodeCost::kOutputTriangle;
}

std::uint64_t lodChainBytes(const DecodeDensity& density, int lods) {
    return lods > 1 ? std::uint64_t(density.triangles) * DecodeCost::kLodChainTriangle : 0;
}

DecodeDensity pricedDensity(const SubdOutline& asset, const DensityRequest& request, DecodeBudget& budget, int lods) {
    DecodeDensity density = decodeDensity(asset, request, budget.name());
    const bool asked = request.segments > 0 || request.triangles > 0;
    while (!asked && density.segments > 1 && !budget.fits(1, decodeOutputBytes(density) + lodChainBytes(density, lods)))
        density = densityAt(asset.cage, density.segments - 1);
    const std::string what = std::to_string(density.triangles) + " triangles (" + std::to_string(density.segments) +
                             (density.segments == 1 ? " segment" : " segments") + " a face edge)";
    budget.spend(std::uint64_t(density.vertices), DecodeCost::kOutputVertex, what);
    budget.spend(std::uint64_t(density.triangles), DecodeCost::kOutputTriangle, what);
    if (lods > 1)
        budget.spend(1, lodChainBytes(density, lods), std::to_string(lods) + " levels of detail from " + what);
    return density;
}

}  // namespace subdfit::codec
