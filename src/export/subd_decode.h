#pragma once
// `subdfit decode`: a shipped .subd file back to what any glTF viewer or engine reads, the
// displaced limit surface as triangles (with the normal map, if the file has one, as the
// material's normalTexture). Reads nothing but the file.
#include <cstdint>
#include <filesystem>
#include <string>

#include "export/output_file.h"
#include "export/subd_format.h"

namespace subdfit::exporter {

// The segments per ptex-face edge decode uses by default: one vertex per map node (the
// density the maps were sampled at), or 8 without maps.
int defaultDecodeSegments(const SubdAsset& asset);

// The most triangles decode writes: a surface past it is refused before it is tessellated.
inline constexpr std::uint64_t kMaxDecodeTriangles = std::uint64_t(1) << 24;

// How densely decode tessellates: `segments` per ptex-face edge when given (`--tess`, 1..64),
// else the nearest to `triangles` triangles (`--triangles`), else the default.
struct DecodeDensity {
    int segments = 0;
    std::uint64_t triangles = 0;
};

// The triangles `segments` per edge give on `asset` (its ptex faces that have a surface).
std::uint64_t decodedTriangles(const SubdAsset& asset, int segments);

// The segments `density` asks for on `asset`: the one density choice of `subdfit decode` and the
// web decoder (apps/web). Throws subdfit::Error naming `name` for a density out of range or a
// surface of more than kMaxDecodeTriangles.
int decodeSegments(const SubdAsset& asset, const DecodeDensity& density, const std::string& name);

// Writes `out` (.glb) atomically. Throws subdfit::Error naming the file for a bad input or an
// impossible tessellation.
WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out, const DecodeDensity& density = {});

}  // namespace subdfit::exporter
