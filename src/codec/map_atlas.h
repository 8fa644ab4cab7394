#pragma once
// Packs the per-node maps into ordinary images a DCC tool or a glTF viewer can use: one tile of
// (T+1)×(T+1) pixels per ptex face, pixel (x0+i, y0+j) holding node (i, j) of that face.
//
// Why (T+1) and not T: with the nodes *on* pixel centres, GPU bilinear filtering at
//   UV = ((x0 + 0.5 + u·T) / W, (y0 + 0.5 + v·T) / H)      (glTF convention, v down the image)
// interpolates exactly the four nodes surface::sampleBilinear would, and never reaches a
// neighbouring tile (no mips: each tile is a separate chart). Shared border nodes are simply
// written into every tile that uses them.
//
// The layout and the pixels, which the web decoder (apps/web) compiles too; the image files
// (PNG, EXR) are export/map_images.h's.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/vec2.hpp>

#include "surface/surface_maps.h"
#include "surface/texel_layout.h"

namespace subdfit::codec {

struct AtlasLayout {
    int resolution = 0;  // T, cells per tile edge
    int tileSize = 0;    // T + 1 pixels
    int columns = 0, rows = 0;
    int width = 0, height = 0;            // pixels
    std::vector<glm::ivec2> tileOrigins;  // per ptex face: pixel (x0, y0) of its node (0, 0)
};

// ceil(sqrt(F)) columns, tiles row-major from the top-left, image row 0 at the top.
AtlasLayout atlasLayout(const surface::TexelLayout& layout);

// The glTF TEXCOORD of ptex (u, v) on `face`, per the formula above.
glm::vec2 atlasUv(const AtlasLayout& atlas, int face, float u, float v);

// Row-major from the top, width × height values; pixels outside every tile are 0.
std::vector<float> displacementAtlas(const AtlasLayout& atlas, const surface::SurfaceMaps& maps);
// Row-major from the top, width × height × 3 values, rgb = n·0.5 + 0.5 in 16-bit units with
// n = normalize(x, y, 1); pixels outside every tile hold the flat normal (0, 0, 1).
std::vector<std::uint16_t> normalAtlas(const AtlasLayout& atlas, const surface::SurfaceMaps& maps);

// The appearance maps' images on `atlas` (atlasLayout(maps.appearanceLayout)): the sRGB base
// colour, glTF's metallic-roughness image (G roughness, B metallic, R occlusion: 1 without),
// or, carried on an atlas, the normal texture (rgb as glTF's) and the sRGB emissive.
enum class AppearanceImage { BaseColor, MetallicRoughness, NormalTexture, Emissive };
// The same image's RGB8 pixels (rows top first), and the inverse: node values as the mean of
// every pixel that holds the node (a node on a tile border is in several tiles).
std::vector<std::uint8_t> appearancePixels(const AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                           AppearanceImage which);
std::vector<float> nodesFromAppearancePixels(const AtlasLayout& atlas, const surface::TexelLayout& layout,
                                             std::span<const std::uint8_t> rgb, AppearanceImage which);
// The occlusion in a metallic-roughness image's red channel, one value per node.
std::vector<float> occlusionFromPixels(const AtlasLayout& atlas, const surface::TexelLayout& layout,
                                       std::span<const std::uint8_t> rgb);

// The normal map resampled (bilinearly) onto the appearance lattice, as `layout` and `normal` of
// the result: a glTF material's textures then share one set of texture coordinates.
surface::SurfaceMaps normalOnAppearanceLattice(const surface::SurfaceMaps& maps);

}  // namespace subdfit::codec
