#pragma once
// The map atlases (codec/map_atlas.h) as image files, through OpenImageIO: PNG bytes to embed
// in a GLB or a USDZ, and the files a fit writes beside its cage.
#include <filesystem>
#include <string>
#include <vector>

#include "codec/map_atlas.h"
#include "io/output_file.h"
#include "surface/surface_maps.h"

namespace subdfit::exporter {

// normal.png's bytes (16-bit RGB, or 8-bit with `eightBit`), for writing and for embedding in a
// GLB. Requires a normal map.
std::vector<unsigned char> encodeNormalPng(const codec::AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                           bool eightBit = false);

// 8-bit PNG bytes of one of the appearance images on `atlas`.
std::vector<unsigned char> encodeAppearancePng(const codec::AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                               codec::AppearanceImage which);

// PNG bytes of `channels`-channel pixels, rows top first; `name` names the image in errors.
std::vector<unsigned char> encodePng(int width, int height, int channels, const void* pixels, bool sixteenBit,
                                     const std::string& name);

// Which files writeMapAtlases may write; a map that is absent is skipped either way.
struct AtlasOutputs {
    bool displacement = true;  // displacement.exr, one FLOAT channel "Y"
    bool normal = true;        // normal.png, 16-bit RGB
    bool manifest = true;      // maps.json: the layout, the UV formula and the units
    // What an asset ships rather than what a fit keeps: HALF displacement and an 8-bit normal
    // map, about half the bytes, below the precision a renderer resolves.
    bool compact = false;
};

// Writes into the existing folder `dir`, each file atomically: displacement.exr and normal.png
// on the geometric maps' atlas, base_color.png and metallic_roughness.png on the appearance
// maps' (maps.json describes both, the latter under "appearance"). Throws subdfit::Error naming the
// file that could not be written.
std::vector<io::WrittenFile> writeMapAtlases(const std::filesystem::path& dir, const surface::SurfaceMaps& maps,
                                             const AtlasOutputs& outputs = {});

}  // namespace subdfit::exporter
