#include "export/gltf/surface_glb.h"

#include "codec/map_atlas.h"
#include "export/map_images.h"
#include "export/surface_mesh.h"

namespace subdfit::exporter {

SurfaceGlb surfaceGlb(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps, int segments) {
    const SurfaceTextures present = SurfaceTextures::of(maps);
    SurfaceGlb glb{.mesh = surfaceGltfMesh(cage, maps, present, segments), .textures = {}};
    FittedTextures& textures = glb.textures;
    if (const NormalImage normal = surfaceNormalImage(maps, present); !normal.empty())
        textures.normalPng = encodePng(normal.width, normal.height, 3, normal.rgb.data(), true, "normal.png");
    if (present.baseColor) {
        const codec::AtlasLayout atlas = codec::atlasLayout(maps.appearanceLayout);
        textures.baseColorPng = encodeAppearancePng(atlas, maps, codec::AppearanceImage::BaseColor);
        if (present.metallicRoughness) {
            textures.metallicRoughnessPng = encodeAppearancePng(atlas, maps, codec::AppearanceImage::MetallicRoughness);
            textures.occlusionInMetallicRoughness = present.occlusion;
        }
        if (present.normalTexture)
            textures.normalPng = encodeAppearancePng(atlas, maps, codec::AppearanceImage::NormalTexture);
        if (present.emissive) textures.emissivePng = encodeAppearancePng(atlas, maps, codec::AppearanceImage::Emissive);
    }
    withoutUnreadAttributes(glb.mesh, glb.textures);
    return glb;
}

void withoutUnreadAttributes(GltfMesh& mesh, const FittedTextures& textures) {
    if (textures.normalPng.empty()) mesh.tangents.clear();
    if (!textures.any()) mesh.uvs.clear();
}

io::WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                                const surface::SurfaceMaps& maps, int segments, MeshCoding coding) {
    const SurfaceGlb glb = surfaceGlb(cage, maps, segments);
    return writeFittedGlb(path, glb.mesh, glb.textures, coding);
}

}  // namespace subdfit::exporter
