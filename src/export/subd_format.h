#pragma once
// The shipped asset, one file: `.subd`, version 5. What a user ships is the control cage (with its
// OpenSubdiv tags) and the maps' node values, quantised and entropy-coded; `subdfit decode`
// turns it back into triangles. Layout (little-endian):
//
//   header   "SUBD" | u16 version (5) | u16 flags | u32 section count
//   section  4-byte tag | u32 stored bytes | u32 raw bytes | stored bytes (a zstd frame)
//   trailer  u64 XXH3-64 of every byte before it
//
// Sections, each at most once: CAGE first (required), then any of DISP, NORM, AUVS, BCOL, MTRG,
// NTEX, EMIS. Raw
// contents, varints being LEB128 and signed ones zigzag:
//
//   CAGE  u8 coding (0 plain, 1 Draco) | varint vertices, varint faces | f32 origin[3],
//         f32 extent | u8 position bits b; positions are q = round((p − origin) / extent ·
//         (2^b − 1)) per axis; then
//         plain: vertices × 3 u16 (x of all, then y, then z) | face sizes: varint each | face
//           indices: signed varint deltas from the previous index;
//         Draco: varint n | n bytes of a Draco triangle mesh (edgebreaker) whose POSITION
//           attribute holds q as 3 integers; points with equal q are one vertex, numbered in
//           order of first appearance | one u8 per Draco triangle: bit k set when its edge
//           from corner k to k + 1 lies inside a polygon; triangles joined across such edges
//           are one face, faces ordered by their first triangle, each starting at the first
//           corner of that triangle whose edge is on the face's boundary;
//         then u8 boundary, u8 face-varying boundary, u8 crease method, u8 triangle rule |
//         creases: varint n, then n × (varint v0, varint v1, f32 sharpness) | corners:
//         varint n, n × (varint vertex, f32 sharpness) | holes: varint n, n × varint face
//   DISP  varint map resolution T | varint node count | f32 center, f32 step | residuals of
//         the heights (export/node_coding.h), on the texel layout the decoder rebuilds from
//         the decoded cage (surface/texel_layout.h)
//   NORM  the same with two channels (tangent-space x, y): T, node count, then per channel
//         (f32 center, f32 step), then the residuals of x, then of y
//   BCOL  the sRGB base colour on a lattice of its own (the appearance lattice): varint T |
//         varint node count | u8 coding (1: JPEG) | varint n | n bytes of a JPEG of the atlas
//         (export/map_atlas.h: a (T+1)² pixel tile per ptex face, ceil(sqrt(F)) columns); a
//         node's value is the mean of its pixels in every tile that holds it
//   MTRG  the same for roughness (green) and metallic (blue) on the appearance lattice; coding
//         2: its red channel is the occlusion (glTF's occlusion-roughness-metallic packing)
//   AUVS  (before BCOL and MTRG) the appearance is in a texture atlas instead: the corners'
//         atlas coordinates (export/atlas_uv_coding.h); BCOL and MTRG then hold T = size − 1,
//         size² nodes and a size × size JPEG, the texture itself (glTF texture coordinates)
//   NTEX  (with AUVS) the reference's normal texture on the atlas, as BCOL: rgb as glTF's, in
//         the tangent frame of the atlas coordinates
//   EMIS  the reference's sRGB emission on the appearance lattice (tiles or the atlas), as BCOL
//
// Flags: bit 0, with DISP: the limit surface's normal shades the displaced surface (the heights
// only place it; surface::ShadingNormal); otherwise the displaced surface's own. Other bits: 0.
//
// Heights are in the cage's units along the limit normal. (Version 1 had no coding byte and
// 16-bit plain positions; its files are refused with the version named. Version 3 had no AUVS
// and reads as version 5; version 4 coded AUVS without prediction, and reads as version 5 when
// it has none.)
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
