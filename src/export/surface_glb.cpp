#include "export/surface_glb.h"

#include "export/glb_writer.h"
#include "export/gltf_mesh.h"
#include "export/map_atlas.h"
#include "surface/tessellation.h"

namespace subdfit::exporter {

WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                            const surface::SurfaceMaps& maps, int segments, bool draco) {
    const auto atlas = atlasLayout(maps.layout.resolution > 0 ? maps.layout : surface::buildTexelLayout(cage, 1));
    const auto normalPng = maps.hasNormal() ? encodeNormalPng(atlas, maps) : std::vector<unsigned char>{};
    return writeFittedGlb(path, gltfMesh(surface::tessellate(cage, maps, segments), atlas), normalPng, draco);
}

}  // namespace subdfit::exporter
