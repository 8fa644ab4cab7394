#include "export/surface_glb.h"

#include "export/glb_writer.h"
#include "export/gltf_mesh.h"
#include "export/map_atlas.h"
#include "surface/tessellation.h"

namespace subdfit::exporter {

WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                            const surface::SurfaceMaps& maps, int segments, bool draco) {
    const auto tessellation = surface::tessellate(cage, maps, segments);
    if (!maps.hasBaseColor()) {
        const auto atlas = atlasLayout(maps.layout.resolution > 0 ? maps.layout : surface::buildTexelLayout(cage, 1));
        const auto normalPng = maps.hasNormal() ? encodeNormalPng(atlas, maps) : std::vector<unsigned char>{};
        return writeFittedGlb(path, gltfMesh(tessellation, atlas), normalPng, draco);
    }
    // With a material every texture sits on the appearance atlas, so that one TEXCOORD_0
    // serves them all (any viewer reads it); the normal map is resampled onto its lattice.
    const auto atlas = atlasLayout(maps.appearanceLayout);
    FittedTextures textures{.baseColorPng = encodeAppearancePng(atlas, maps, AppearanceImage::BaseColor)};
    if (maps.hasMetallicRoughness())
        textures.metallicRoughnessPng = encodeAppearancePng(atlas, maps, AppearanceImage::MetallicRoughness);
    if (maps.hasNormal()) textures.normalPng = encodeNormalPng(atlas, normalOnAppearanceLattice(maps));
    return writeFittedGlb(path, gltfMesh(tessellation, atlas), textures, draco);
}

}  // namespace subdfit::exporter
