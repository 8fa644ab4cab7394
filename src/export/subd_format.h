#pragma once
// The shipped asset, one file: `.subd`, version 5. What a user ships is the control cage (with its
// OpenSubdiv tags) and the maps' node values, quantised and entropy-coded; `subdfit decode`
// turns it back into triangles. docs/asset-subd-format.md specifies the bytes (header, sections,
// trailer) and which versions a reader takes; encodeSubd writes them and decodeSubd checks every
// part before it trusts it.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "export/map_atlas.h"
#include "export/output_file.h"
#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::exporter {

inline constexpr std::uint16_t kSubdVersion = 5;

// The cage as fitted and the maps laid out on the cage as it decodes (shippableAsset makes one).
struct SubdAsset {
    mesh::PolygonMesh cage;
    surface::SurfaceMaps maps;  // layout.resolution 0: none
};

struct SubdPrecision {
    int positionBits = 14;      // per coordinate, over the cage's bounding cube (8..16), as Draco's default for meshes
    int displacementBits = 12;  // over the heights' range (1..24)
    int normalBits = 10;        // over each tangent-space channel's range (1..24)
    int appearanceQuality = 90;  // JPEG quality of the appearance maps' atlases (1..100)

    // What `--map-bits` and `--appearance-quality` ask for: heights at `mapBits`, normals at
    // most 10 (finer than a renderer resolves a normal).
    static SubdPrecision forMapBits(int mapBits, int appearanceQuality = 90) {
        return {.displacementBits = mapBits, .normalBits = mapBits < 10 ? mapBits : 10, .appearanceQuality = appearanceQuality};
    }
};

std::vector<unsigned char> encodeSubd(const SubdAsset& asset, const SubdPrecision& precision = {});

// `name` names the data in errors. Throws subdfit::Error ("name: problem") for anything that is
// not a whole, checksummed version-3, 4 or 5 file whose cage and maps are sound.
SubdAsset decodeSubd(std::span<const unsigned char> bytes, const std::string& name);

// An appearance image (BCOL, MTRG, NTEX, EMIS) as the file carries it, still encoded: its size is
// read from its header and checked against its lattice's atlas, its pixels are not decoded.
struct ShippedImage {
    AppearanceImage which = AppearanceImage::BaseColor;
    bool occlusion = false;  // a metallic-roughness image whose red channel is the occlusion
    int width = 0, height = 0;
    const char* mimeType = "image/jpeg";
    std::vector<unsigned char> bytes;
};

// A .subd file read whole but for its appearance images' pixels: the cage, the geometric maps,
// the appearance's lattice and atlas coordinates (no appearance values), and the images.
struct ShippedSubd {
    SubdAsset asset;
    std::vector<ShippedImage> images;  // in the file's order, each kind at most once
};

// What decodeSubd reads before it decodes the images (with OpenImageIO): the one reader of the
// format, shared with the web decoder (apps/web), which leaves the images to the browser.
// Throws subdfit::Error as decodeSubd.
ShippedSubd readShippedSubd(std::span<const unsigned char> bytes, const std::string& name);

WrittenFile writeSubd(const std::filesystem::path& path, const SubdAsset& asset, const SubdPrecision& precision = {});
SubdAsset readSubd(const std::filesystem::path& path);

// The asset to encode for `cage` and `maps` (laid out on `cage`): the decoder rebuilds the texel
// layout from the decoded cage, whose vertices and faces may be renumbered (export/cage_coding.h)
// and whose node welding may differ in degenerate places, so the node values are carried over
// to that layout tile by tile.
SubdAsset shippableAsset(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                         int positionBits = SubdPrecision{}.positionBits);

}  // namespace subdfit::exporter
