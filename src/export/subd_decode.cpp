#include "export/subd_decode.h"

#include "export/surface_glb.h"
#include "util/error.h"

namespace subdfit::exporter {

int defaultDecodeSegments(const SubdAsset& asset) { return asset.maps.layout.resolution > 0 ? asset.maps.layout.resolution : 8; }

WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out, int segments) {
    const SubdAsset asset = readSubd(subd);
    if (segments == 0) segments = defaultDecodeSegments(asset);
    if (segments < 1 || segments > 64) throw Error("invalid option: --tess: must be in 1..64, got " + std::to_string(segments));
    return writeSurfaceGlb(out, asset.cage, asset.maps, segments, false);
}

}  // namespace subdfit::exporter
