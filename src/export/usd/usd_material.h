#pragma once
// A cage's maps as a UsdPreviewSurface material: the heights as `inputs:displacement` (scalar
// along the normal, in the cage's units), the appearance as its colour, metallic, roughness,
// occlusion, emission and normal inputs, each read by a UsdUVTexture from an image of the package.
//
// The heights' image is a 16-bit grey PNG of the map atlas (codec/map_atlas.h: a (T+1)² pixel
// tile per ptex face, the nodes on pixel centres, so bilinear filtering at full resolution is
// exactly subdfit's bilinear tile), read raw through face-varying `st`; its scale and bias
// turn a texel t in [0, 1] into the height lo + t·(hi − lo), lo and hi the heights' range.
// The appearance is on an atlas of its own (per-face tiles, or the reference's texture atlas),
// read through `st1`.
#include <functional>
#include <string>
#include <vector>

#include "export/usd/usd_cage.h"
#include "export/usd/usda_text.h"
#include "surface/surface_maps.h"

namespace subdfit::exporter {

struct UsdTextureFile {
    std::string name;  // e.g. "displacement.png"
    std::vector<unsigned char> bytes;
};

// The texture coordinates `maps` need on the cage: "st" for the heights (and a normal map),
// "st1" for the appearance; none for a cage without maps.
std::vector<UsdTexCoords> usdTexCoords(const surface::SurfaceMaps& maps);

// True when `maps` has anything a material shows.
bool hasUsdMaterial(const surface::SurfaceMaps& maps);

// The Material prim at `path` (its last element the prim's name) into `layer`, inside the
// current block; returns the images it reads, which `assetPath` names as the layer refers to
// them (e.g. the name itself inside the package). Requires hasUsdMaterial(maps).
std::vector<UsdTextureFile> writeMaterialPrim(usda::Layer& layer, const surface::SurfaceMaps& maps,
                                              const std::string& path,
                                              const std::function<std::string(const std::string& name)>& assetPath);

}  // namespace subdfit::exporter
