#include "export/surface_mesh.h"

#include "codec/map_atlas.h"
#include "surface/appearance_atlas.h"
#include "surface/tessellation.h"
#include "util/error.h"

namespace subdfit::exporter {

SurfaceTextures SurfaceTextures::of(const surface::SurfaceMaps& maps) {
    return {.baseColor = maps.hasBaseColor(),
            .metallicRoughness = maps.hasMetallicRoughness(),
            .occlusion = maps.hasMetallicRoughness() && !maps.occlusion.empty(),
            .normalTexture = !maps.normalTexture.empty(),
            .emissive = !maps.emissive.empty(),
            .normalMap = maps.hasNormal()};
}

SurfaceMaterial surfaceMaterial(const SurfaceTextures& textures) {
    SurfaceMaterial m;
    if (textures.baseColor) {
        m.baseColorFactor = {1.0, 1.0, 1.0, 1.0};
        m.roughnessFactor = 1.0;
        if (textures.metallicRoughness) m.metallicFactor = 1.0;
    }
    if (textures.emissive) m.emissiveFactor = {1.0, 1.0, 1.0};
    return m;
}

GltfMesh surfaceGltfMesh(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                         const SurfaceTextures& textures, int segments) {
    if (!textures.baseColor) {
        // Without maps the texcoords still name each face's tile: a one-cell atlas, whose layout
        // needs only the number of tiles.
        surface::TexelLayout tiles;
        tiles.resolution = 1;
        for (int n : cage.faceSizes) tiles.ptexFaceCount += n == 4 ? 1 : n;
        return gltfMesh(surface::tessellate(cage, maps, segments),
                        codec::atlasLayout(maps.layout.resolution > 0 ? maps.layout : tiles));
    }
    if (!maps.appearanceAtlas.present())
        return gltfMesh(surface::tessellate(cage, maps, segments), codec::atlasLayout(maps.appearanceLayout));
    // The appearance in the reference's own atlas: the texture as it is, addressed by the
    // corners' coordinates blended across each face. Its one TEXCOORD_0 leaves no room for a
    // normal map on tiles (the search pairs an atlas with heights alone); the reference's own
    // normal texture is in the frame of the atlas coordinates, which the tessellation's
    // TANGENTs give (the fit's frame, not one each viewer derives its own way).
    if (textures.normalMap) throw Error("a fitted normal map beside an appearance atlas");
    surface::Tessellation tessellation = surface::tessellate(cage, maps, segments);
    GltfMesh mesh =
        gltfMesh(std::move(tessellation), codec::atlasLayout(maps.appearanceLayout));  // keeps the ptex coordinates
    if (!textures.normalTexture) mesh.tangents.clear();
    for (size_t k = 0; k < mesh.uvs.size(); ++k) {
        const surface::PtexPoint& p = tessellation.ptex[k];
        mesh.uvs[k] = surface::atlasUvAt(maps.appearanceAtlas, p.face, p.u, p.v);
    }
    return mesh;
}

NormalImage surfaceNormalImage(const surface::SurfaceMaps& maps, const SurfaceTextures& textures) {
    if (!maps.hasNormal()) return {};
    // With a material every texture sits on the appearance atlas, so that one TEXCOORD_0 serves
    // them all (any viewer reads it): the normal map is resampled onto its lattice.
    if (textures.baseColor) {
        const surface::SurfaceMaps onLattice = codec::normalOnAppearanceLattice(maps);
        const codec::AtlasLayout atlas = codec::atlasLayout(onLattice.layout);
        return {atlas.width, atlas.height, codec::normalAtlas(atlas, onLattice)};
    }
    const codec::AtlasLayout atlas = codec::atlasLayout(maps.layout);
    return {atlas.width, atlas.height, codec::normalAtlas(atlas, maps)};
}

}  // namespace subdfit::exporter
