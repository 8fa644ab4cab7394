#pragma once
// The shipped asset, one file: `.subd`, version 11. What a user ships is the control cage (with its
// OpenSubdiv tags) and the maps' node values, quantised and entropy-coded; `subdfit decode`
// turns it back into triangles. docs/asset-subd-format.md specifies the bytes (header, sections,
// trailer) and which versions a reader takes; encodeSubd writes them and decodeSubd checks every
// part before it trusts it, pricing every count the file states against a decode budget
// (codec/decode_budget.h) before anything of that size is allocated.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "codec/map_atlas.h"
#include "codec/node_coding.h"
#include "io/output_file.h"
#include "kinds/map_kinds.h"
#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::codec {

inline constexpr std::uint16_t kSubdVersion = 11;
// zstd's level for every section: the asset is written once and shipped many times.
inline constexpr int kSubdZstdLevel = 19;

class DecodeBudget;

// The cage as fitted and the maps laid out on the cage as it decodes (shippableAsset makes one).
struct SubdAsset {
    mesh::PolygonMesh cage;
    surface::SurfaceMaps maps;          // layout.resolution 0: none
    std::uint32_t decodeTriangles = 0;  // the reference's triangle count; 0: unknown
    // How a decoded file coded its heights (the reader fills it; the writer ignores it).
    std::optional<ChannelQuantisation> heightsCoding{};
};

// A coarser asset the heights' first levels make on their own (docs/asset-subd-format.md,
// "Prefixes"): the levels down to the lattice of `resolution` (the map's own divided by a power of
// two) coded at `bits`, then refined to the map's bits. 0: none.
struct EmbeddedPrefix {
    int resolution = 0, bits = 0;
    // What those levels hold, on the map's layout (its coarse lattice's nodes are read): the
    // heights best on the coarse lattice alone; empty: the map's.
    std::vector<float> heights{};
    // Where `heights` are a decoded asset's (SubdAsset::heightsCoding, at `resolution`): its center,
    // step and leans, so that the levels code its values exactly, and its cage section
    // (ShippedSubd::cageSection), written byte for byte: the asset's cage is the one being
    // encoded, in its order, and the levels' coding order is the asset's own. The prefix is then
    // that asset's cage and heights.
    std::optional<ChannelQuantisation> coding{};
    std::vector<unsigned char> cageSection{};
};

struct SubdPrecision {
    int positionBits = 14;       // per coordinate, over the cage's bounding cube (8..16), as Draco's default for meshes
    int displacementBits = 12;   // over the heights' range (1..24)
    int normalBits = 10;         // over each tangent-space channel's range (1..24)
    int appearanceQuality = 90;  // JPEG quality of the appearance maps' atlases (1..100)
    EmbeddedPrefix prefix{};     // of the heights

    // What `--map-bits`, `--appearance-quality` and `--position-bits` ask for: heights at
    // `mapBits`, normals at most 10 (finer than a renderer resolves a normal).
    static SubdPrecision forMapBits(int mapBits, int appearanceQuality = 90, int positionBits = 14) {
        return {.positionBits = positionBits,
                .displacementBits = mapBits,
                .normalBits = mapBits < 10 ? mapBits : 10,
                .appearanceQuality = appearanceQuality};
    }
    // The bits of a node-coded (geometric) kind's values.
    int bits(kinds::MapKind kind) const { return kind == kinds::MapKind::NormalMap ? normalBits : displacementBits; }
};

std::vector<unsigned char> encodeSubd(const SubdAsset& asset, const SubdPrecision& precision = {});

// What a file is before its maps are built: its cage, decoded, and what its headers state.
struct SubdOutline {
    const mesh::PolygonMesh& cage;
    std::uint32_t decodeTriangles = 0;
    int mapResolution = 0;  // of the displacement / normal tiles; 0: none
};

// Whether the bytes are a whole file or may be its first bytes (a file cut short, a download
// under way). A prefix decodes as far as it goes: the sections wholly in it, and of a node-coded
// map cut short the levels wholly in it, its finer nodes interpolated (codec/node_coding.h).
// Its cage must be whole; a section after it is absent. A whole file read as a Prefix is read
// whole.
enum class SubdEnding { Whole, Prefix };

// `name` names the data in errors. Throws subdfit::Error ("name: problem") for anything that is
// not a whole, checksummed version-3 to 7 file whose cage and maps are sound, or that would take
// more than `budget` (by default a DecodeBudget of its own) to decode. Every section's counts
// are checked and priced, and the cage decoded, before any map is built; then `priced` is
// called (a caller's chance to price its own work from the outline, e.g. the triangles to write).
SubdAsset decodeSubd(std::span<const unsigned char> bytes, const std::string& name, DecodeBudget* budget = nullptr,
                     const std::function<void(const SubdOutline&)>& priced = {}, SubdEnding ending = SubdEnding::Whole);

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
    // Each section's tag and the bytes it takes in the file (its 12-byte head included), in order.
    std::vector<std::pair<std::string, std::size_t>> sectionBytes;
    int positionBits = 0;                    // per cage coordinate, as coded
    std::vector<unsigned char> cageSection;  // the CAGE section's raw bytes
};

// What decodeSubd reads before it decodes the images (with OpenImageIO): the one reader of the
// format, shared with the web decoder (apps/web), which leaves the images to the browser. The
// images' pixels are priced in `budget` with their sections. Throws subdfit::Error as decodeSubd.
ShippedSubd readShippedSubd(std::span<const unsigned char> bytes, const std::string& name,
                            DecodeBudget* budget = nullptr, const std::function<void(const SubdOutline&)>& priced = {},
                            SubdEnding ending = SubdEnding::Whole);

// The fewest first bytes of a whole file `bytes` that decode as a prefix (SubdEnding::Prefix): its
// header and cage section, a bare cage; 0 where the file's version is read whole only (before
// 10). Throws subdfit::Error as readShippedSubd.
std::size_t cageEnd(std::span<const unsigned char> bytes, const std::string& name);

io::WrittenFile writeSubd(const std::filesystem::path& path, const SubdAsset& asset,
                          const SubdPrecision& precision = {});
// `firstBytes`: read only the file's first bytes, as a prefix (whole where the file is no longer).
SubdAsset readSubd(const std::filesystem::path& path, DecodeBudget* budget = nullptr,
                   const std::function<void(const SubdOutline&)>& priced = {},
                   std::size_t firstBytes = std::numeric_limits<std::size_t>::max());

// The asset to encode for `cage` and `maps` (laid out on `cage`), decoding by default to
// `decodeTriangles` (0: unknown): the decoder rebuilds the texel
// layout from the decoded cage, whose vertices and faces may be renumbered (codec/cage_coding.h)
// and whose node welding may differ in degenerate places, so the node values are carried over
// to that layout tile by tile.
SubdAsset shippableAsset(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                         int positionBits = SubdPrecision{}.positionBits, std::uint32_t decodeTriangles = 0);

}  // namespace subdfit::codec
