#include "export/engine/error_density.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cstdio>
#include <limits>
#include <string>
#include <map>

#include "export/engine/surface_error.h"
#include "geometry/surface_distance.h"
#include "surface/tessellation.h"
#include "util/warnings.h"

namespace subdfit::exporter {
namespace {

double diagonalOf(const mesh::PolygonMesh& mesh) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return mesh.positions.empty() ? 0.0 : double(glm::length(hi - lo));
}

std::string printableNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

}  // namespace

ErrorDensity densityWithin(const codec::SubdAsset& asset, const ErrorBound& bound, codec::DecodeBudget& budget) {
    int finest = codec::kMaxDecodeSegments;
    while (finest > 1 && (codec::densityAt(asset.cage, finest).triangles > codec::kMaxDecodeTriangles ||
                          !budget.fits(1, decodeOutputBytes(codec::densityAt(asset.cage, finest)))))
        --finest;
    const codec::DecodeDensity reference = codec::densityAt(asset.cage, finest);
    budget.spend(1, decodeOutputBytes(reference),
                 "the reference tessellation of --max-error (" + std::to_string(reference.triangles) + " triangles)");
    const mesh::PolygonMesh fine = surface::triangleMesh(surface::tessellate(asset.cage, asset.maps, finest));
    ErrorDensity out{.density = reference,
                     .maxDistance = 0.0,
                     .bound = bound.ofDiagonal ? bound.value * diagonalOf(fine) : bound.value,
                     .referenceSegments = finest};
    // Below what float positions resolve no density but the finest can be told within the
    // bound: decode at it, and say so, rather than bisect down to it for nothing.
    if (const double floor = kResolvableFraction * diagonalOf(fine); out.bound < floor) {
        warn(budget.name() + ": --max-error " + printableNumber(out.bound) + " is below what the surface resolves (" +
             printableNumber(floor) + ", a millionth of its diagonal): decoding at the finest density, " +
             std::to_string(finest) + " segments a face edge");
        out.clamped = true;
        return out;
    }
    std::map<int, double> errors{{finest, 0.0}};
    auto error = [&](int segments) {
        if (!errors.count(segments)) {
            const mesh::PolygonMesh coarse =
                surface::triangleMesh(surface::tessellate(asset.cage, asset.maps, segments));
            errors[segments] = geometry::surfaceDistance(coarse, fine, kErrorSamples).hausdorff;
        }
        return errors[segments];
    };
    int lo = 1, hi = finest;  // error(hi) is within the bound
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (error(mid) <= out.bound) hi = mid;
        else lo = mid + 1;
    }
    out.density = codec::densityAt(asset.cage, hi);
    out.maxDistance = error(hi);
    return out;
}

}  // namespace subdfit::exporter
