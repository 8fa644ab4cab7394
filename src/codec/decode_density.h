#pragma once
// How densely a decoder of asset.subd tessellates its surface: `segments` per ptex-face edge,
// the same on every face (surface/tessellation.h), 2·segments² triangles a ptex face. By default
// around the triangle count the file records (the reference's: simplify and fit write it), else,
// for files that record none, one derived from the cage: one vertex per map node (8 segments
// without maps), at most kFallbackTriangles. Pure arithmetic on the cage's face sizes and holes,
// so that any front end (`subdfit decode`, the WebAssembly decoder) calls it as it is.
#include <cstdint>
#include <string>

#include "codec/decode_budget.h"
#include "codec/subd_format.h"

namespace subdfit::codec {

// The most triangles a decode writes: asked for (--triangles, --tess) or by default.
inline constexpr std::int64_t kMaxDecodeTriangles = std::int64_t(1) << 22;
// The default for a file that records no triangle count: an engine-sized mesh.
inline constexpr std::int64_t kFallbackTriangles = std::int64_t(1) << 20;
inline constexpr int kMaxDecodeSegments = 64;

// What a user asks for; 0: the default. At most one of them.
struct DensityRequest {
    int segments = 0;
    std::int64_t triangles = 0;
};

struct DecodeDensity {
    int segments = 1;
    std::int64_t triangles = 0;  // that the segments give
    std::int64_t vertices = 0;   // (segments + 1)² per ptex face: faces do not share them
};

// Ptex faces that have a surface (a quad is one, an n-gon n; holes have none).
std::int64_t surfacePtexFaces(const mesh::PolygonMesh& cage);

DecodeDensity densityAt(const mesh::PolygonMesh& cage, int segments);

// The density for `request` on a file (named `name` in errors) whose outline is known: its
// cage and its headers, before any map is built. Throws subdfit::Error naming the file for a
// request beyond kMaxDecodeTriangles or kMaxDecodeSegments, or OptionError for one that is
// malformed (both given, negative).
DecodeDensity decodeDensity(const SubdOutline& asset, const DensityRequest& request, const std::string& name);
DecodeDensity decodeDensity(const SubdAsset& asset, const DensityRequest& request, const std::string& name);

// What writing `density` costs a decoder (DecodeCost::kOutputVertex, kOutputTriangle).
std::uint64_t decodeOutputBytes(const DecodeDensity& density);

// decodeDensity for a file being read (readShippedSubd's `priced`, named by `budget`), with the
// vertices and triangles a decoder writes at it spent from `budget`, and `lods` levels of detail
// (DecodeCost::kLodChainTriangle per triangle of the first, where lods > 1): the default gives way
// to what the budget has left (fewer segments), a density asked for does not (it is refused).
DecodeDensity pricedDensity(const SubdOutline& asset, const DensityRequest& request, DecodeBudget& budget,
                            int lods = 1);

// What a chain of `lods` levels below `density` costs a decoder (0 for one level).
std::uint64_t lodChainBytes(const DecodeDensity& density, int lods);

}  // namespace subdfit::codec
