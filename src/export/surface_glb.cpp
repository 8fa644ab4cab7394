#include "export/surface_glb.h"

#include "export/glb_writer.h"
#include "export/map_atlas.h"
#include "export/surface_mesh.h"

namespace subdfit::exporter {

WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                            const surface::SurfaceMaps& maps, int segments, bool draco) {
    const SurfaceTextures present = SurfaceTextures::of(maps);
    const GltfMesh mesh = surfaceGltfMesh(cage, maps, present, segments);
    FittedTextures textures;
    if (const NormalImage normal = surfaceNormalImage(maps, present); !normal.empty())
        textures.normalPng = encodePng(normal.width, normal.height, 3, normal.rgb.data(), true, "normal.png");
    if (present.baseColor) {
        const AtlasLayout atlas = atlasLayout(maps.appearanceLayout);
        textures.baseColorPng = encodeAppearancePng(atlas, maps, AppearanceImage::BaseColor);
        if (present.metallicRoughness) {
            textures.metallicRoughnessPng = encodeAppearancePng(atlas, maps, AppearanceImage::MetallicRoughness);
            textures.occlusionInMetallicRoughness = present.occlusion;
        }
        if (present.normalTexture) textures.normalPng = encodeAppearancePng(atlas, maps, AppearanceImage::NormalTexture);
        if (present.emissive) textures.emissivePng = encodeAppearancePng(atlas, maps, AppearanceImage::Emissive);
    }
    return writeFittedGlb(path, mesh, textures, draco);
}

}  // namespace subdfit::exporter
