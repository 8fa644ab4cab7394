#pragma once
// The shipped asset, one file: `.subd`, version 1. What a user ships is the control cage (with its
// OpenSubdiv tags) and the maps' node values, quantised and entropy-coded; `subdfit decode`
// turns it back into triangles. Layout (little-endian):
//
//   header   "SUBD" | u16 version (1) | u16 flags (0) | u32 section count
//   section  4-byte tag | u32 stored bytes | u32 raw bytes | stored bytes (a zstd frame)
//   trailer  u64 XXH3-64 of every byte before it
//
// Sections, each at most once: CAGE first (required), then DISP and/or NORM. Raw contents,
// varints being LEB128 and signed ones zigzag:
//
//   CAGE  varint vertices, varint faces | f32 origin[3], f32 extent | u8 position bits b
//         | positions: vertices × 3 u16 (x of all, then y, then z), each q = round((p − origin)
//           / extent · (2^b − 1)) | face sizes: varint each | face indices: signed varint
//           deltas from the previous index | u8 boundary, u8 face-varying boundary,
//           u8 crease method, u8 triangle rule | creases: varint n, then n × (varint v0,
//           varint v1, f32 sharpness) | corners: varint n, n × (varint vertex, f32 sharpness)
//           | holes: varint n, n × varint face
//   DISP  varint map resolution T | varint node count | f32 center, f32 step | residuals of
//         the heights (export/node_coding.h), on the texel layout the decoder rebuilds from
//         the decoded cage (surface/texel_layout.h)
//   NORM  the same with two channels (tangent-space x, y): T, node count, then per channel
//         (f32 center, f32 step), then the residuals of x, then of y
//
// Heights are in the cage's units along the limit normal.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "export/output_file.h"
#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::exporter {

inline constexpr std::uint16_t kSubdVersion = 1;

struct SubdAsset {
    mesh::PolygonMesh cage;
    surface::SurfaceMaps maps;  // layout.resolution 0: none
};

struct SubdPrecision {
    int positionBits = 16;      // per coordinate, over the cage's bounding cube (8..16)
    int displacementBits = 12;  // over the heights' range (1..24)
    int normalBits = 10;        // over each tangent-space channel's range (1..24)
};

std::vector<unsigned char> encodeSubd(const SubdAsset& asset, const SubdPrecision& precision = {});

// `name` names the data in errors. Throws subdfit::Error ("name: problem") for anything that is
// not a whole, checksummed version-1 file whose cage and maps are sound.
SubdAsset decodeSubd(std::span<const unsigned char> bytes, const std::string& name);

WrittenFile writeSubd(const std::filesystem::path& path, const SubdAsset& asset, const SubdPrecision& precision = {});
SubdAsset readSubd(const std::filesystem::path& path);

// The cage as the decoder will see it (positions quantised).
mesh::PolygonMesh quantisedCage(const mesh::PolygonMesh& cage, int positionBits = SubdPrecision{}.positionBits);

// The asset to encode for `cage` and `maps` (laid out on any cage of the same topology): the
// decoder rebuilds the texel layout from the quantised cage, whose node welding may differ in
// degenerate places, so the node values are carried over to that layout by (face, i, j).
SubdAsset shippableAsset(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                         int positionBits = SubdPrecision{}.positionBits);

}  // namespace subdfit::exporter
