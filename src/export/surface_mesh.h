#pragma once
// The displaced limit surface as decode ships it, before anything is written: the glTF mesh with
// the texture coordinates its material's images are on, the normal map's pixels and the
// material's factors. writeSurfaceGlb (fit's fitted.glb, `subdfit decode`) and the web decoder
// (apps/web) both build on these, so a page draws the triangles `decode` writes.
#include <array>
#include <cstdint>
#include <vector>

#include "export/gltf_mesh.h"
#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::exporter {

// Which images the material has, whether as node values (SurfaceTextures::of) or still encoded
// in a .subd (the web decoder knows them from its sections).
struct SurfaceTextures {
    bool baseColor = false, metallicRoughness = false, occlusion = false, normalTexture = false, emissive = false;
    bool normalMap = false;  // the fitted normal map (maps.normal), drawn as the normalTexture

    static SurfaceTextures of(const surface::SurfaceMaps& maps);
};

// glTF's factors for those images: with a base colour the fitted material (white, rough 1,
// metallic 1 with a metallic-roughness image, else 0); without one (a normal map on a reference
// with no material) the surface DCC tools draw where there is no material, Blender's default
// (0.8 grey, metallic 0, roughness 0.5); an emissive image glows at factor 1.
struct SurfaceMaterial {
    std::array<double, 4> baseColorFactor{0.8, 0.8, 0.8, 1.0};
    double metallicFactor = 0.0, roughnessFactor = 0.5;
    std::array<double, 3> emissiveFactor{0.0, 0.0, 0.0};
};
SurfaceMaterial surfaceMaterial(const SurfaceTextures& textures);

// `segments` per ptex-face edge (surface::tessellate), texcoords on the atlas the images are on:
// the appearance's (tiles, or the reference's own atlas through the corners' coordinates) with
// a base colour, else the geometric maps' (a one-cell layout without maps). TANGENTs stay unless
// the images are on the reference's atlas without its normal texture. Throws subdfit::Error for
// maps no decoder draws (a fitted normal map beside an atlas).
GltfMesh surfaceGltfMesh(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                         const SurfaceTextures& textures, int segments);

// The fitted normal map on the mesh's texcoords' atlas (resampled onto the appearance lattice
// with a base colour): 16-bit rgb = n·0.5 + 0.5, rows top first. Empty without a normal map.
struct NormalImage {
    int width = 0, height = 0;
    std::vector<std::uint16_t> rgb;
    bool empty() const { return rgb.empty(); }
};
NormalImage surfaceNormalImage(const surface::SurfaceMaps& maps, const SurfaceTextures& textures);

}  // namespace subdfit::exporter
