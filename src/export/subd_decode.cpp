#include "export/subd_decode.h"

#include "export/glb_writer.h"
#include "export/gltf_mesh.h"
#include "export/map_atlas.h"
#include "surface/tessellation.h"
#include "util/error.h"

namespace subdfit::exporter {

int defaultDecodeSegments(const SubdAsset& asset) { return asset.maps.layout.resolution > 0 ? asset.maps.layout.resolution : 8; }

WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out, int segments) {
    const SubdAsset asset = readSubd(subd);
    if (segments == 0) segments = defaultDecodeSegments(asset);
    if (segments < 1 || segments > 64) throw Error("invalid option: --tess: must be in 1..64, got " + std::to_string(segments));
    const auto& maps = asset.maps;
    const auto atlas = atlasLayout(maps.layout.resolution > 0 ? maps.layout : surface::buildTexelLayout(asset.cage, 1));
    const auto normalPng = maps.hasNormal() ? encodeNormalPng(atlas, maps) : std::vector<unsigned char>{};
    return writeFittedGlb(out, gltfMesh(surface::tessellate(asset.cage, maps, segments), atlas), normalPng, false);
}

}  // namespace subdfit::exporter
