#include "export/surface_glb.h"

#include "export/glb_writer.h"
#include "export/gltf_mesh.h"
#include "export/map_atlas.h"
#include "surface/tessellation.h"
#include "util/error.h"

namespace subdfit::exporter {

WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                            const surface::SurfaceMaps& maps, int segments, bool draco) {
    const auto tessellation = surface::tessellate(cage, maps, segments);
    if (!maps.hasBaseColor()) {
        const auto atlas = atlasLayout(maps.layout.resolution > 0 ? maps.layout : surface::buildTexelLayout(cage, 1));
        const auto normalPng = maps.hasNormal() ? encodeNormalPng(atlas, maps) : std::vector<unsigned char>{};
        return writeFittedGlb(path, gltfMesh(tessellation, atlas), normalPng, draco);
    }
    if (maps.appearanceAtlas.present()) {
        // The appearance in the reference's own atlas: the texture as it is, addressed by the
        // corners' coordinates blended across each face. Its one TEXCOORD_0 leaves no room for a
        // normal map on tiles (the search pairs an atlas with heights alone); the reference's
        // own normal texture is in the frame of the atlas coordinates, which the tessellation's
        // TANGENTs give (the fit's frame, not one each viewer derives its own way).
        SUBDFIT_CHECK(!maps.hasNormal());
        const auto grid = atlasLayout(maps.appearanceLayout);
        FittedTextures textures{.baseColorPng = encodeAppearancePng(grid, maps, AppearanceImage::BaseColor)};
        if (maps.hasMetallicRoughness()) {
            textures.metallicRoughnessPng = encodeAppearancePng(grid, maps, AppearanceImage::MetallicRoughness);
            textures.occlusionInMetallicRoughness = !maps.occlusion.empty();
        }
        if (!maps.normalTexture.empty()) textures.normalPng = encodeAppearancePng(grid, maps, AppearanceImage::NormalTexture);
        if (!maps.emissive.empty()) textures.emissivePng = encodeAppearancePng(grid, maps, AppearanceImage::Emissive);
        GltfMesh mesh = gltfMesh(tessellation, grid);
        if (maps.normalTexture.empty()) mesh.tangents.clear();
        for (size_t k = 0; k < mesh.uvs.size(); ++k) {
            const surface::PtexPoint& p = tessellation.ptex[k];
            mesh.uvs[k] = surface::atlasUvAt(maps.appearanceAtlas, p.face, p.u, p.v);
        }
        return writeFittedGlb(path, mesh, textures, draco);
    }
    // With a material every texture sits on the appearance atlas, so that one TEXCOORD_0
    // serves them all (any viewer reads it); the normal map is resampled onto its lattice.
    const auto atlas = atlasLayout(maps.appearanceLayout);
    FittedTextures textures{.baseColorPng = encodeAppearancePng(atlas, maps, AppearanceImage::BaseColor)};
    if (maps.hasMetallicRoughness()) {
        textures.metallicRoughnessPng = encodeAppearancePng(atlas, maps, AppearanceImage::MetallicRoughness);
        textures.occlusionInMetallicRoughness = !maps.occlusion.empty();
    }
    if (!maps.emissive.empty()) textures.emissivePng = encodeAppearancePng(atlas, maps, AppearanceImage::Emissive);
    if (maps.hasNormal()) textures.normalPng = encodeNormalPng(atlas, normalOnAppearanceLattice(maps));
    return writeFittedGlb(path, gltfMesh(tessellation, atlas), textures, draco);
}

}  // namespace subdfit::exporter
