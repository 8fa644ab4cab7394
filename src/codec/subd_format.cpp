#include "codec/subd_format.h"

#include <zstd.h>
#include <zstd_errors.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>

#include "codec/atlas_uv_coding.h"
#include "codec/byte_stream.h"
#include "codec/cage_coding.h"
#include "codec/decode_budget.h"
#include "codec/map_atlas.h"
#include "codec/node_coding.h"
#include "io/image_header.h"
#include "io/image_io.h"
#include "io/input_file.h"
#include "mesh/input_limits.h"
#include "mesh/mesh_validation.h"
#include "surface/texel_layout.h"
#include "util/hash.h"
#include "util/printable.h"

namespace subdfit::codec {
namespace {

using Tag = std::array<char, 4>;
using kinds::MapKind;
// The map kinds' sections are theirs (kinds/map_kinds.h); these are the file's own.
constexpr Tag kCage{'C', 'A', 'G', 'E'}, kAtlasUvs{'A', 'U', 'V', 'S'}, kNormalTexture{'N', 'T', 'E', 'X'},
    kEmissive{'E', 'M', 'I', 'S'};
constexpr Tag kBaseColor = kinds::info(MapKind::BaseColor).section,
              kMetallicRoughness = kinds::info(MapKind::MetallicRoughness).section;

// The geometric kind whose section `tag` is (node-coded on the cage's lattice); null for another.
const kinds::MapKindInfo* geometricSection(const Tag& tag) {
    const kinds::MapKindInfo* kind = kinds::kindWithSection(tag);
    return kind && kind->lattice == kinds::MapLattice::Geometric ? kind : nullptr;
}
constexpr std::uint32_t kMostSections = 8;
constexpr char kMagic[4] = {'S', 'U', 'B', 'D'};
constexpr std::uint16_t kLimitShadingFlag = 1;
// The largest raw section of a whole asset: a million-face cage plain-coded, a 4096² JPEG.
constexpr std::uint32_t kMaxRawSection = 1u << 26;
// What a section's first raw bytes must hold for its counts to be read (varints and a byte).
constexpr std::size_t kSectionHeadBytes = 64;
// The fewest raw bytes between two points where a node-coded section's frame is flushed.
constexpr std::size_t kLeastFlushedBytes = 1024;

std::string tagName(const Tag& tag) { return printable(std::string_view(tag.data(), tag.size())); }

// The first ptex face of every face, then the count: a quad has one, an n-gon n
// (Far::PtexIndices).
std::vector<int> firstPtexFaces(const mesh::PolygonMesh& cage) {
    std::vector<int> first{0};
    for (int n : cage.faceSizes) first.push_back(first.back() + (n == 4 ? 1 : n));
    return first;
}

// Node values on `from` (laid out on `cage`) carried onto `to` (the same resolution, laid out on
// `decoded`): each decoded tile takes the values of the tile it came from, turned by the face's
// rotation (a quad's (i, j) rotates; an n-gon's per-corner tiles are renumbered).
std::vector<float> carriedValues(const mesh::PolygonMesh& cage, const surface::TexelLayout& from,
                                 const std::vector<float>& values, int channels, const mesh::PolygonMesh& decoded,
                                 const surface::TexelLayout& to, const CageCorrespondence& correspondence) {
    const int T = from.resolution;
    const auto fromPtex = firstPtexFaces(cage), toPtex = firstPtexFaces(decoded);
    // A quad's corners in its own (i, j), counter-clockwise from corner 0.
    constexpr int kCornerI[4] = {0, 1, 1, 0}, kCornerJ[4] = {0, 0, 1, 1};
    std::vector<float> out(size_t(to.nodeCount) * size_t(channels), 0.0f);
    auto copy = [&](int fromFace, int i, int j, int toFace, int ti, int tj) {
        const size_t a = size_t(from.node(fromFace, i, j)), b = size_t(to.node(toFace, ti, tj));
        for (int c = 0; c < channels; ++c)
            out[b * size_t(channels) + size_t(c)] = values[a * size_t(channels) + size_t(c)];
    };
    for (int f = 0; f < cage.faceCount(); ++f) {
        const int n = cage.faceSizes[size_t(f)], r = correspondence.rotation[size_t(f)];
        const int g = correspondence.face[size_t(f)];
        for (int j = 0; j <= T; ++j)
            for (int i = 0; i <= T; ++i) {
                if (n != 4) {
                    for (int k = 0; k < n; ++k)
                        copy(fromPtex[size_t(f)] + (k + r) % n, i, j, toPtex[size_t(g)] + k, i, j);
                    continue;
                }
                // Decoded corner k is the cage's corner k + r: bilinear in the corners' (i, j).
                const int w[4] = {(T - i) * (T - j), i * (T - j), i * j, (T - i) * j};
                int si = 0, sj = 0;
                for (int k = 0; k < 4; ++k) {
                    si += w[k] * kCornerI[(k + r) % 4];
                    sj += w[k] * kCornerJ[(k + r) % 4];
                }
                copy(fromPtex[size_t(f)], si / T, sj / T, toPtex[size_t(g)], i, j);
            }
    }
    return out;
}

// An atlas's corner coordinates carried onto the decoded cage as carriedValues carries tiles:
// decoded corner k of a quad is the cage's corner k + r; an n-gon's per-corner faces renumber.
surface::AppearanceAtlas carriedCornerUvs(const mesh::PolygonMesh& cage, const surface::AppearanceAtlas& atlas,
                                          const mesh::PolygonMesh& decoded, const CageCorrespondence& correspondence) {
    const auto fromPtex = firstPtexFaces(cage), toPtex = firstPtexFaces(decoded);
    surface::AppearanceAtlas out{.size = atlas.size, .cornerUvs = std::vector<glm::vec2>(4 * size_t(toPtex.back()))};
    for (int f = 0; f < cage.faceCount(); ++f) {
        const int n = cage.faceSizes[size_t(f)], r = correspondence.rotation[size_t(f)];
        const int g = correspondence.face[size_t(f)];
        for (int k = 0; k < (n == 4 ? 1 : n); ++k)
            for (int c = 0; c < 4; ++c) {
                const size_t to =
                    n == 4 ? 4 * size_t(toPtex[size_t(g)]) + size_t(c) : 4 * size_t(toPtex[size_t(g)] + k) + size_t(c);
                const size_t from = n == 4 ? 4 * size_t(fromPtex[size_t(f)]) + size_t((c + r) % 4)
                                           : 4 * size_t(fromPtex[size_t(f)] + (k + r) % n) + size_t(c);
                out.cornerUvs[to] = atlas.cornerUvs[from];
            }
    }
    return out;
}

surface::SurfaceMaps carriedMaps(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps,
                                 const mesh::PolygonMesh& decoded, const CageCorrespondence& to) {
    surface::SurfaceMaps out;
    out.shadingNormal = maps.shadingNormal;
    if (maps.layout.resolution > 0 && maps.kinds().geometric()) {
        out.layout = surface::buildTexelLayout(decoded, maps.layout.resolution);
        for (const kinds::MapKindInfo& kind : kinds::kMapKinds)
            if (kind.lattice == kinds::MapLattice::Geometric && maps.has(kind.kind))
                out.values(kind.kind) =
                    carriedValues(cage, maps.layout, maps.values(kind.kind), kind.channels, decoded, out.layout, to);
    }
    if (maps.appearanceAtlas.present() && maps.kinds().appearance()) {
        // The texels stay; the corners' coordinates follow their faces and corners.
        out.setAppearance(maps);
        out.appearanceAtlas = carriedCornerUvs(cage, maps.appearanceAtlas, decoded, to);
    } else if (maps.appearanceLayout.resolution > 0 && maps.kinds().appearance()) {
        out.appearanceLayout = surface::buildTexelLayout(decoded, maps.appearanceLayout.resolution);
        for (const kinds::MapKindInfo& kind : kinds::kMapKinds)
            if (kind.lattice == kinds::MapLattice::Appearance && maps.has(kind.kind))
                out.values(kind.kind) = carriedValues(cage, maps.appearanceLayout, maps.values(kind.kind),
                                                      kind.channels, decoded, out.appearanceLayout, to);
        // The reference's occlusion (shipped in the metallic-roughness image's red) and emission.
        if (maps.hasMetallicRoughness() && !maps.occlusion.empty())
            out.occlusion =
                carriedValues(cage, maps.appearanceLayout, maps.occlusion, 1, decoded, out.appearanceLayout, to);
        if (!maps.emissive.empty())
            out.emissive =
                carriedValues(cage, maps.appearanceLayout, maps.emissive, 3, decoded, out.appearanceLayout, to);
    }
    return out;
}

// A section's raw bytes and where a prefix of them may end: its zstd frame is flushed there, so
// that what a stream has delivered up to each point inflates on its own (codec/node_coding.h).
struct RawSection {
    Tag tag;
    std::vector<unsigned char> bytes;
    std::vector<std::size_t> prefixEnds;
    std::size_t embeddedEnd = 0;  // where an embedded coding's coarse levels end: flushed whatever its size
};

// `prefix`: the coarse lattice and bits of an embedded coding (ChannelQuantisation), or none.
void writeMaps(const surface::TexelLayout& layout, const std::vector<float>& values, int channels, int bits,
               const EmbeddedPrefix& prefix, ByteWriter& out, std::vector<std::size_t>& passEnds,
               std::size_t& embeddedEnd) {
    out.putVarint(std::uint64_t(layout.resolution));
    out.putVarint(std::uint64_t(layout.nodeCount));
    std::vector<ChannelQuantisation> q;
    for (int c = 0; c < channels; ++c) {
        q.push_back(quantisationFor(values, channels, c, bits));
        if (prefix.resolution > 0 && prefix.bits < bits) {
            q.back().coarsePasses = passesOfLattice(layout.resolution, prefix.resolution);
            q.back().coarseShift = bits - prefix.bits;
            if (prefix.coding) {  // the asset's grid and leans: its values code exactly
                q.back().center = prefix.coding->center;
                q.back().step = std::ldexp(prefix.coding->step, -q.back().coarseShift);
                q.back().cornerLean = prefix.coding->cornerLean;
                q.back().interpolatedLean = prefix.coding->interpolatedLean;
            }
        }
        out.put<float>(q.back().center);
        out.put<float>(q.back().step);
    }
    passEnds.push_back(out.bytes().size());  // the counts, before any level
    for (int c = 0; c < channels; ++c) {
        const std::size_t first = passEnds.size();
        encodeNodes(layout, values, channels, c, q[size_t(c)], out, &passEnds, prefix.heights);
        if (c == 0 && q[0].coarsePasses > 0) embeddedEnd = passEnds[first + size_t(q[0].coarsePasses) - 1];
    }
}

// A map section's lattice: its resolution and node count, checked against the one the cage
// makes (built on the first map of that lattice, the same for the next). Before it is built,
// the count is checked against the bounds the cage implies (interior nodes are each tile's own,
// border ones at most each tile's); its cost was priced with the file's sections.
void readLattice(ByteReader& in, const mesh::PolygonMesh& cage, surface::TexelLayout& layout) {
    // Tiles have at most 64 cells a side; an atlas lattice is its texture's (surface::kMaxAtlasSize).
    const int resolution =
        in.getIndex(layout.resolution > 0 ? std::uint64_t(layout.resolution) + 1 : 65, "map resolution");
    if (resolution < 1) throw Error(in.what() + ": map resolution 0");
    const std::uint64_t nodes = in.getVarint();
    if (layout.resolution == 0) {
        const std::uint64_t ptex = std::uint64_t(firstPtexFaces(cage).back()), side = std::uint64_t(resolution) + 1;
        const std::uint64_t most = ptex * side * side, fewest = ptex * (side - 2) * (side - 2);
        if (nodes > most || nodes < fewest)
            throw Error(in.what() + ": node count " + std::to_string(nodes) +
                        " does not match the cage's texel layout (" + std::to_string(fewest) + " to " +
                        std::to_string(most) + " nodes at resolution " + std::to_string(resolution) + ")");
        layout = surface::buildTexelLayout(cage, resolution);
    }
    if (layout.resolution != resolution) throw Error(in.what() + ": the maps disagree on their resolution");
    if (nodes != std::uint64_t(layout.nodeCount))
        throw Error(in.what() + ": node count does not match the cage's texel layout");
}

// `coded` (one per channel) receives how each channel was coded, `levels` the level passes of the
// first channel that were decoded (all of them but in a prefix).
std::vector<float> readMaps(ByteReader& in, const mesh::PolygonMesh& cage, int channels, NodeStream stream,
                            surface::TexelLayout& layout, NodeEnding ending, std::vector<ChannelQuantisation>& coded,
                            int& levels) {
    readLattice(in, cage, layout);
    std::vector<ChannelQuantisation> q(static_cast<size_t>(channels));
    for (auto& channel : q) {
        channel.center = in.get<float>();
        channel.step = in.get<float>();
        if (!std::isfinite(channel.center) || !(channel.step > 0.0f) || !std::isfinite(channel.step))
            throw Error(in.what() + ": bad quantisation");
    }
    std::vector<float> values(size_t(layout.nodeCount) * size_t(channels));
    coded.assign(size_t(channels), {});
    for (int c = 0; c < channels; ++c) {
        const int present =
            decodeNodes(layout, values, channels, c, q[size_t(c)], in, stream, ending, &coded[size_t(c)]);
        if (c > 0) continue;
        if (present == 0) return {};                   // a prefix without even the corners: no map
        const int refinement = coded[0].coarsePasses;  // its index in the stream, where there is one
        levels = refinement > 0 && present > refinement ? present - 1 : present;
    }
    return values;
}

// A map cut short (`levels` of its passes decoded) whose levels make a whole coarser lattice,
// the only geometric map: laid out at that lattice's resolution, as a file made for it on the
// same cage holds it (and a renderer draws it), instead of interpolated on the finer one.
void keepTheWholeLattice(const mesh::PolygonMesh& cage, surface::SurfaceMaps& maps, const kinds::MapKindInfo& kind,
                         int levels) {
    for (const kinds::MapKindInfo& other : kinds::kMapKinds)
        if (other.lattice == kinds::MapLattice::Geometric && other.kind != kind.kind && maps.has(other.kind)) return;
    const int T = maps.layout.resolution;
    for (int spacing = 2; spacing <= T; spacing *= 2) {
        if (T % spacing != 0 || passesOfLattice(T, T / spacing) > levels) continue;
        const surface::TexelLayout coarse = surface::buildTexelLayout(cage, T / spacing);
        const std::vector<float>& fine = maps.values(kind.kind);
        std::vector<float> values(size_t(coarse.nodeCount) * size_t(kind.channels));
        for (int face = 0; face < coarse.ptexFaceCount; ++face)
            for (int j = 0; j <= coarse.resolution; ++j)
                for (int i = 0; i <= coarse.resolution; ++i)
                    for (int c = 0; c < kind.channels; ++c)
                        values[size_t(coarse.node(face, i, j)) * size_t(kind.channels) + size_t(c)] =
                            fine[size_t(maps.layout.node(face, i * spacing, j * spacing)) * size_t(kind.channels) +
                                 size_t(c)];
        maps.layout = coarse;
        maps.values(kind.kind) = std::move(values);
        return;
    }
}

// An appearance map as a JPEG of its atlas (codec/map_atlas.h), 8-bit sRGB: textures carry
// detail node prediction codes poorly, and what JPEG drops a viewer hardly sees. A metallic-
// roughness image whose red channel holds the occlusion says so by its coding.
constexpr std::uint8_t kJpegCoding = 1, kJpegWithOcclusionCoding = 2;

void writeAppearance(const surface::SurfaceMaps& maps, AppearanceImage which, int quality, ByteWriter& out) {
    const surface::TexelLayout& layout = maps.appearanceLayout;
    out.putVarint(std::uint64_t(layout.resolution));
    out.putVarint(std::uint64_t(layout.nodeCount));
    const bool occlusion = which == AppearanceImage::MetallicRoughness && !maps.occlusion.empty();
    out.put<std::uint8_t>(occlusion ? kJpegWithOcclusionCoding : kJpegCoding);
    const AtlasLayout atlas = atlasLayout(layout);
    const auto rgb = appearancePixels(atlas, maps, which);
    io::DecodedImage image{atlas.width, atlas.height, std::vector<std::uint8_t>(rgb.size() / 3 * 4, 255)};
    for (size_t p = 0; p < rgb.size() / 3; ++p)
        for (int c = 0; c < 3; ++c) image.rgba[4 * p + size_t(c)] = rgb[3 * p + size_t(c)];
    // Full-resolution chroma for tiles: the atlas packs unrelated tiles side by side, and halved
    // chroma would bleed colour across their borders. A texture atlas is an ordinary image.
    const bool tiles = !maps.appearanceAtlas.present();
    const auto jpeg = io::encodeImage(image, atlas.width, atlas.height, io::ImageFormat::Jpeg, quality, tiles);
    out.putVarint(jpeg.size());
    out.putBytes({jpeg.data(), jpeg.size()});
}

// An appearance image's section: its lattice (built on the first), its coding and its JPEG,
// whose header must give the size of the lattice's atlas (its pixels were priced with the
// file's sections; they are not decoded here).
ShippedImage readAppearance(ByteReader& in, const mesh::PolygonMesh& cage, AppearanceImage which,
                            surface::SurfaceMaps& maps) {
    surface::TexelLayout& layout = maps.appearanceLayout;
    if (maps.appearanceAtlas.present() && layout.resolution == 0)
        layout = surface::atlasLattice(maps.appearanceAtlas.size);
    readLattice(in, cage, layout);
    const auto coding = in.get<std::uint8_t>();
    const bool occlusion = which == AppearanceImage::MetallicRoughness && coding == kJpegWithOcclusionCoding;
    if (coding != kJpegCoding && !occlusion) throw Error(in.what() + ": unknown appearance coding");
    const auto bytes = in.take(in.getCount(1, "image byte"));
    const AtlasLayout atlas = atlasLayout(layout);
    const std::optional<io::ImageHeader> header = io::jpegHeader(bytes);
    if (!header) throw Error(in.what() + ": not a JPEG image");
    // Checked alike by every decoder (a browser draws what libjpeg would refuse): its markers.
    if (const std::string problem = io::jpegStructureProblem(bytes); !problem.empty())
        throw Error(in.what() + ": a damaged JPEG (" + problem + ")");
    if (header->width != atlas.width || header->height != atlas.height)
        throw Error(in.what() + ": the image is " + std::to_string(header->width) + " x " +
                    std::to_string(header->height) + ", the atlas " + std::to_string(atlas.width) + " x " +
                    std::to_string(atlas.height));
    return {.which = which,
            .occlusion = occlusion,
            .width = header->width,
            .height = header->height,
            .bytes = {bytes.begin(), bytes.end()}};
}

Tag tagOf(AppearanceImage which) {
    switch (which) {
        case AppearanceImage::BaseColor: return kBaseColor;
        case AppearanceImage::MetallicRoughness: return kMetallicRoughness;
        case AppearanceImage::NormalTexture: return kNormalTexture;
        case AppearanceImage::Emissive: return kEmissive;
    }
    throw Error("unknown appearance image");
}

// A shipped image's pixels as the node values of its kind in `maps` (whose appearance lattice
// the reader built); `what` names its section in errors.
void decodeAppearance(const ShippedImage& shipped, const std::string& what, surface::SurfaceMaps& maps) {
    const io::DecodedImage image = io::decodeImage(shipped.bytes.data(), shipped.bytes.size(), what);
    if (image.width != shipped.width || image.height != shipped.height)
        throw Error(what + ": the image decodes to " + std::to_string(image.width) + " x " +
                    std::to_string(image.height) + ", its header says " + std::to_string(shipped.width) + " x " +
                    std::to_string(shipped.height));
    const surface::TexelLayout& layout = maps.appearanceLayout;
    std::vector<std::uint8_t> rgb(size_t(image.width) * size_t(image.height) * 3);
    for (size_t p = 0; p < rgb.size() / 3; ++p)
        for (int c = 0; c < 3; ++c) rgb[3 * p + size_t(c)] = image.rgba[4 * p + size_t(c)];
    const AtlasLayout atlas = atlasLayout(layout);
    std::vector<float> values = nodesFromAppearancePixels(atlas, layout, rgb, shipped.which);
    switch (shipped.which) {
        case AppearanceImage::BaseColor: maps.baseColor = std::move(values); break;
        case AppearanceImage::MetallicRoughness: maps.metallicRoughness = std::move(values); break;
        case AppearanceImage::NormalTexture: maps.normalTexture = std::move(values); break;
        case AppearanceImage::Emissive: maps.emissive = std::move(values); break;
    }
    if (shipped.occlusion) maps.occlusion = occlusionFromPixels(atlas, layout, rgb);
}

void putSection(ByteWriter& file, const RawSection& section) {
    // Each frame carries a checksum of its content (version 7): a section damaged inside is
    // refused by every decoder alike, whatever its zstd would make of it otherwise.
    std::unique_ptr<ZSTD_CCtx, decltype(&ZSTD_freeCCtx)> context(ZSTD_createCCtx(), &ZSTD_freeCCtx);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_compressionLevel, kSubdZstdLevel);
    ZSTD_CCtx_setParameter(context.get(), ZSTD_c_checksumFlag, 1);
    const std::vector<unsigned char>& raw = section.bytes;
    ZSTD_CCtx_setPledgedSrcSize(context.get(), raw.size());  // the frame states its size
    std::vector<unsigned char> stored(ZSTD_compressBound(raw.size()) + 64 * (section.prefixEnds.size() + 1));
    ZSTD_outBuffer out{stored.data(), stored.size(), 0};
    std::size_t from = 0;
    auto compress = [&](std::size_t to, ZSTD_EndDirective directive) {
        ZSTD_inBuffer in{raw.data() + from, to - from, 0};
        std::size_t left;
        do {
            left = ZSTD_compressStream2(context.get(), &out, &in, directive);
            if (ZSTD_isError(left)) throw Error(std::string("zstd: ") + ZSTD_getErrorName(left));
        } while (left != 0);
        from = to;
    };
    // A block costs its header and its own entropy tables: a pass of a few dozen bytes joins the next.
    for (const std::size_t end : section.prefixEnds)
        if ((end >= from + kLeastFlushedBytes || end == section.embeddedEnd) && end > from && end < raw.size())
            compress(end, ZSTD_e_flush);
    compress(raw.size(), ZSTD_e_end);
    file.putBytes({reinterpret_cast<const unsigned char*>(section.tag.data()), 4});
    file.put<std::uint32_t>(std::uint32_t(out.pos));
    file.put<std::uint32_t>(std::uint32_t(raw.size()));
    file.putBytes({stored.data(), out.pos});
}

// The first `n` raw bytes of a section's zstd frame (fewer when it holds fewer), without
// inflating the rest.
std::vector<unsigned char> sectionHead(std::span<const unsigned char> stored, std::size_t n) {
    std::unique_ptr<ZSTD_DCtx, decltype(&ZSTD_freeDCtx)> context(ZSTD_createDCtx(), &ZSTD_freeDCtx);
    std::vector<unsigned char> head(n);
    ZSTD_outBuffer out{head.data(), head.size(), 0};
    ZSTD_inBuffer in{stored.data(), stored.size(), 0};
    while (out.pos < out.size) {
        const std::size_t before = out.pos + in.pos;
        const std::size_t result = ZSTD_decompressStream(context.get(), &out, &in);
        if (ZSTD_isError(result) || result == 0 || out.pos + in.pos == before) break;
    }
    head.resize(out.pos);
    return head;
}

// Whether a zstd frame says it carries a checksum of its content: bit 2 of its frame header
// descriptor, the byte after the 4-byte magic (RFC 8878, 3.1.1.1.1).
bool hasContentChecksum(std::span<const unsigned char> frame) { return frame.size() > 4 && (frame[4] & 0x04) != 0; }

// Whether a frame inflates whole to `rawSize` bytes (at most kMaxRawSection) with its checksum right.
bool frameIntact(std::span<const unsigned char> frame, std::size_t rawSize) {
    std::vector<unsigned char> raw(rawSize);
    const std::size_t got = ZSTD_decompress(raw.data(), raw.size(), frame.data(), frame.size());
    return !ZSTD_isError(got) && got == rawSize;
}

// One entry of the section table, read before any section is inflated.
struct SectionEntry {
    Tag tag;
    std::span<const unsigned char> stored;
    std::uint32_t rawSize = 0;
    std::vector<unsigned char> head;  // the first raw bytes: the section's counts
    bool cut = false;                 // the last section of a prefix, its frame cut short
    std::string what() const { return tagName(tag) + " section"; }
};

// The cage's counts from its section's head, priced; what the section may hold at most.
std::uint64_t priceCage(const SectionEntry& cage, const std::string& name, DecodeBudget& budget) {
    ByteReader in(cage.head, name + ": " + cage.what());
    in.get<std::uint8_t>();
    const std::uint64_t vertices = in.getVarint(), faces = in.getVarint();
    if (vertices > std::uint64_t(mesh::kMaxVertices) || faces > std::uint64_t(mesh::kMaxTriangles))
        throw Error(in.what() + ": more vertices or faces than subdfit reads");
    budget.spend(faces, DecodeCost::kCageFace, "a cage of " + std::to_string(faces) + " faces");
    budget.spend(vertices, DecodeCost::kCageVertex, "a cage of " + std::to_string(vertices) + " vertices");
    // Positions, and per face at most kMaxCageFaceSize corners of an index, a Draco flag, an
    // edge's crease; per vertex a corner tag; per face a hole (codec/cage_coding.h).
    return kSectionHeadBytes + 30 * vertices + (5 + 1 + 24) * std::uint64_t(mesh::kMaxCageFaceSize) * faces + 8 * faces;
}

// The costs of the sections after the cage, from their heads, before any is built: each lattice
// (the maps' tiles, the appearance's tiles or atlas) once, each image at its atlas's size. Returns,
// per section, what it may hold at most; `mapResolution` receives the maps' tile resolution.
std::vector<std::uint64_t> priceMaps(const std::vector<SectionEntry>& sections, const mesh::PolygonMesh& cage,
                                     const std::string& name, DecodeBudget& budget, int& mapResolution) {
    const std::uint64_t ptex = std::uint64_t(firstPtexFaces(cage).back());
    std::uint64_t columns = 1;
    while (columns * columns < ptex) ++columns;
    const std::uint64_t rows = (ptex + columns - 1) / columns;
    std::uint64_t atlasSize = 0;
    bool tilesPriced = false, appearancePriced = false;
    auto priceTiles = [&](std::uint64_t resolution, bool& priced, const std::string& what) {
        const std::uint64_t side = std::min<std::uint64_t>(resolution, 64) + 1;
        if (!priced)
            budget.spend(ptex * side * side, DecodeCost::kLatticeSlot,
                         what + " of " + std::to_string(ptex * side * side) + " tile nodes");
        priced = true;
    };
    std::vector<std::uint64_t> most(sections.size(), 0);
    for (size_t k = 1; k < sections.size(); ++k) {
        const SectionEntry& s = sections[k];
        ByteReader in(s.head, name + ": " + s.what());
        constexpr std::uint64_t kHeader = kSectionHeadBytes;
        if (s.tag == kAtlasUvs) {
            atlasSize = in.getVarint();
            if (atlasSize < 2 || atlasSize > std::uint64_t(surface::kMaxAtlasSize))
                throw Error(in.what() + ": atlas size " + std::to_string(atlasSize) + " out of range (2 to " +
                            std::to_string(surface::kMaxAtlasSize) + ")");
            budget.spend(atlasSize * atlasSize, DecodeCost::kAtlasTexel,
                         "an atlas of " + std::to_string(atlasSize) + " x " + std::to_string(atlasSize));
            budget.spend(4 * ptex, DecodeCost::kLatticeSlot,
                         "the atlas coordinates of " + std::to_string(ptex) + " faces");
            most[k] = kHeader + 4 * ptex * (10 + 10 + 20);  // per corner a count, an index, a residual pair
            continue;
        }
        const std::uint64_t resolution = in.getVarint(), nodes = std::min(in.getVarint(), std::uint64_t(1) << 40);
        const kinds::MapKindInfo* geometric = geometricSection(s.tag);
        if (atlasSize == 0 || geometric) {
            // Interior nodes are each tile's own, border ones at most each tile's.
            const std::uint64_t side = std::min<std::uint64_t>(resolution, 64) + 1;
            const std::uint64_t most = ptex * side * side,
                                fewest = resolution > 64 ? 0 : ptex * (side - 2) * (side - 2);
            if (resolution < 1 || resolution > 64 || nodes > most || nodes < fewest)
                throw Error(in.what() + ": resolution " + std::to_string(resolution) + " and node count " +
                            std::to_string(nodes) + " do not match the cage's texel layout (" + std::to_string(fewest) +
                            " to " + std::to_string(most) + " nodes at resolution 1 to 64)");
        }
        if (geometric) {
            priceTiles(resolution, tilesPriced, "a map lattice");
            mapResolution = int(resolution);
            // Per channel its quantisation, leans and nodes (a residual takes under 10 bytes as a
            // varint or in an entropy-coded block), and each level's block its length and tables.
            constexpr std::uint64_t kMostLevels = 13, kBlockOverhead = 4096;
            most[k] =
                kHeader + std::uint64_t(geometric->channels) * (8 + 2 + 10 * nodes + kMostLevels * kBlockOverhead);
            continue;
        }
        std::uint64_t pixels = atlasSize * atlasSize;
        if (atlasSize == 0) {
            priceTiles(resolution, appearancePriced, "an appearance lattice");
            const std::uint64_t tile = resolution + 1;
            pixels = columns * rows * tile * tile;  // codec/map_atlas.h
        }
        budget.spend(pixels, DecodeCost::kAtlasPixel, "an image of " + std::to_string(pixels) + " pixels");
        in.get<std::uint8_t>();                                                       // coding
        most[k] = kHeader + std::min(in.getVarint(), std::uint64_t(kMaxRawSection));  // the image's bytes
    }
    return most;
}

}  // namespace

SubdAsset shippableAsset(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps, int positionBits,
                         std::uint32_t decodeTriangles) {
    const CodedCage coded = encodeCage(cage, positionBits);
    return SubdAsset{.cage = cage,
                     .maps = carriedMaps(cage, maps, coded.decoded, coded.correspondence),
                     .decodeTriangles = decodeTriangles};
}

std::vector<unsigned char> encodeSubd(const SubdAsset& asset, const SubdPrecision& precision) {
    SUBDFIT_CHECK(precision.positionBits >= 8 && precision.positionBits <= 16);
    std::vector<RawSection> sections;
    CodedCage cage;
    if (precision.prefix.cageSection.empty()) {
        cage = encodeCage(asset.cage, precision.positionBits);
    } else {  // the asset's own, byte for byte: it must be the cage being encoded
        ByteReader in(precision.prefix.cageSection, "the prefix's cage");
        cage = {.bytes = precision.prefix.cageSection, .decoded = decodeCage(in), .correspondence = {}};
        SUBDFIT_CHECK(cage.decoded.positions == asset.cage.positions &&
                      cage.decoded.faceIndices == asset.cage.faceIndices);
    }
    const auto& maps = asset.maps;
    const int ptexFaces = firstPtexFaces(cage.decoded).back();
    SUBDFIT_CHECK(maps.layout.resolution == 0 || maps.layout.ptexFaceCount == ptexFaces);
    SUBDFIT_CHECK(maps.appearanceLayout.resolution == 0 || maps.appearanceAtlas.present() ||
                  maps.appearanceLayout.ptexFaceCount == ptexFaces);
    sections.push_back({kCage, std::move(cage.bytes), {}});
    if (maps.appearanceAtlas.present() && maps.kinds().appearance()) {
        ByteWriter section;
        writeAtlasUvs(cage.decoded, maps.appearanceAtlas, section);
        sections.push_back({kAtlasUvs, std::move(section.bytes()), {}});
    }
    const bool atlas = maps.appearanceAtlas.present();
    for (const auto& [tag, which, present] :
         {std::tuple{kBaseColor, AppearanceImage::BaseColor, maps.hasBaseColor()},
          std::tuple{kMetallicRoughness, AppearanceImage::MetallicRoughness, maps.hasMetallicRoughness()},
          std::tuple{kNormalTexture, AppearanceImage::NormalTexture, atlas && !maps.normalTexture.empty()},
          std::tuple{kEmissive, AppearanceImage::Emissive, !maps.emissive.empty()}}) {
        if (maps.appearanceLayout.resolution == 0 || !present) continue;
        ByteWriter section;
        writeAppearance(maps, which, precision.appearanceQuality, section);
        sections.push_back({tag, std::move(section.bytes()), {}});
    }
    // The node-coded maps last, coarse levels first: a prefix of the file is a coarser asset.
    for (const kinds::MapKindInfo& kind : kinds::kMapKinds) {
        if (kind.lattice != kinds::MapLattice::Geometric || maps.layout.resolution == 0 || !maps.has(kind.kind))
            continue;
        ByteWriter section;
        std::vector<std::size_t> passEnds;
        std::size_t embeddedEnd = 0;
        writeMaps(maps.layout, maps.values(kind.kind), kind.channels, precision.bits(kind.kind),
                  kind.kind == MapKind::Displacement ? precision.prefix : EmbeddedPrefix{}, section, passEnds,
                  embeddedEnd);
        sections.push_back({kind.section, std::move(section.bytes()), std::move(passEnds), embeddedEnd});
    }
    ByteWriter file;
    // Assigned, not inserted: GCC 12 misreads an insert into the still-empty vector
    // (-Wstringop-overflow) once the appearance sections change its inlining.
    file.bytes().assign(std::begin(kMagic), std::end(kMagic));
    file.put<std::uint16_t>(kSubdVersion);
    const bool limitShading = maps.hasDisplacement() && maps.shadingNormal == surface::ShadingNormal::Limit;
    file.put<std::uint16_t>(limitShading ? kLimitShadingFlag : 0);
    file.put<std::uint32_t>(std::uint32_t(sections.size()));
    file.put<std::uint32_t>(asset.decodeTriangles);
    for (const RawSection& section : sections) putSection(file, section);
    const auto& bytes = file.bytes();
    file.put<std::uint64_t>(hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    return std::move(file.bytes());
}

ShippedSubd readShippedSubd(std::span<const unsigned char> bytes, const std::string& name, DecodeBudget* sharedBudget,
                            const std::function<void(const SubdOutline&)>& priced, SubdEnding ending) {
    DecodeBudget ownBudget(name);
    DecodeBudget& budget = sharedBudget ? *sharedBudget : ownBudget;
    if (bytes.size() < 4 || std::memcmp(bytes.data(), kMagic, 4) != 0) throw Error(name + ": not a .subd file");
    if (bytes.size() < 20) throw Error(name + ": truncated");
    ShippedSubd shipped;
    ByteReader header(bytes, name);
    header.take(4);
    const auto version = header.get<std::uint16_t>();
    if (version < 3 || version > kSubdVersion)  // the versions differ in AUVS and the decode triangles
        throw Error(name + ": .subd version " + std::to_string(version) + ", this subdfit reads version " +
                    std::to_string(kSubdVersion));
    // A prefix has no trailer: each section whole in it is checked by its frame's checksum, the
    // one cut short is what a stream delivered so far.
    auto intact = [&] {
        std::uint64_t stored;
        std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
        return hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size() - 8}) == stored;
    };
    const bool whole = intact();
    const bool prefix = ending == SubdEnding::Prefix && !whole;
    if (!prefix && !whole) throw Error(name + ": checksum mismatch (damaged or truncated)");
    if (prefix && version < 10)
        throw Error(name + ": .subd version " + std::to_string(version) + " is read whole only");
    ByteReader in(prefix ? bytes : bytes.first(bytes.size() - 8), name);
    in.take(6);
    auto flags = in.get<std::uint16_t>();
    if ((flags & ~kLimitShadingFlag) != 0) throw Error(name + ": unknown flags");
    const auto count = in.get<std::uint32_t>();
    if (count < 1 || count > kMostSections) throw Error(name + ": " + std::to_string(count) + " sections");

    SubdAsset& asset = shipped.asset;
    if (version >= 6) asset.decodeTriangles = in.get<std::uint32_t>();
    // The section table first: tags, sizes and each section's first bytes, so that everything
    // the file states is checked and priced before anything is inflated or built.
    std::vector<SectionEntry> sections;
    for (std::uint32_t k = 0; k < count; ++k) {
        if (prefix && in.remaining() < 12) break;  // the prefix ends before this section begins
        SectionEntry s;
        std::memcpy(s.tag.data(), in.take(4).data(), 4);
        const auto storedSize = in.get<std::uint32_t>();
        s.rawSize = in.get<std::uint32_t>();
        const bool known = s.tag == kCage || kinds::kindWithSection(s.tag) || s.tag == kAtlasUvs ||
                           s.tag == kNormalTexture || s.tag == kEmissive;
        if (!known) throw Error(name + ": unknown section " + tagName(s.tag));
        const bool again =
            std::any_of(sections.begin(), sections.end(), [&](const SectionEntry& e) { return e.tag == s.tag; });
        if ((k == 0) != (s.tag == kCage) || again) throw Error(name + ": section " + tagName(s.tag) + " out of place");
        if (s.rawSize > kMaxRawSection)
            throw Error(name + ": section " + tagName(s.tag) + " holds " + std::to_string(s.rawSize) +
                        " bytes, more than the " + std::to_string(kMaxRawSection) + " a section may");
        s.cut = prefix && storedSize > in.remaining();
        s.stored = in.take(s.cut ? in.remaining() : storedSize);
        const unsigned long long stated = ZSTD_getFrameContentSize(s.stored.data(), s.stored.size());
        if (s.cut && stated == ZSTD_CONTENTSIZE_ERROR) break;  // not even the frame's header
        if (stated != s.rawSize)
            throw Error(name + ": section " + tagName(s.tag) + " does not decompress to its stated size");
        if (version >= 7 && !hasContentChecksum(s.stored))
            throw Error(name + ": section " + tagName(s.tag) + " has no checksum of its content");
        const std::size_t headBytes = std::min<std::size_t>(s.rawSize, kSectionHeadBytes);
        s.head = sectionHead(s.stored, headBytes);
        // A cut section decodes only where it refines: a node-coded map's levels, counts whole.
        if (s.cut && (!geometricSection(s.tag) || s.head.size() < headBytes)) break;
        shipped.sectionBytes.emplace_back(tagName(s.tag), 12 + s.stored.size());
        sections.push_back(std::move(s));
        if (sections.back().cut) break;
    }
    if (sections.empty() || sections[0].cut)
        throw Error(name + ": the first " + std::to_string(bytes.size()) + " bytes end before the cage does");
    if (!prefix && in.remaining() != 0) throw Error(name + ": trailing bytes after the sections");

    auto inflated = [&](const SectionEntry& s, std::uint64_t most) {
        if (s.rawSize > most)
            throw Error(name + ": section " + tagName(s.tag) + " holds " + std::to_string(s.rawSize) +
                        " bytes, more than its counts allow (" + std::to_string(most) + ")");
        if (s.cut) return sectionHead(s.stored, s.rawSize);  // the blocks that are whole
        std::vector<unsigned char> raw(s.rawSize);
        const std::size_t got = ZSTD_decompress(raw.data(), raw.size(), s.stored.data(), s.stored.size());
        if (ZSTD_isError(got) && ZSTD_getErrorCode(got) == ZSTD_error_checksum_wrong)
            throw Error(name + ": section " + tagName(s.tag) + " fails its checksum (damaged)");
        // A frame of several blocks (flushed where a prefix may end) can break before its checksum.
        if (ZSTD_isError(got) && version >= 7)
            throw Error(name + ": section " + tagName(s.tag) + " is damaged (zstd: " + ZSTD_getErrorName(got) + ")");
        if (ZSTD_isError(got) || got != s.rawSize)
            throw Error(name + ": section " + tagName(s.tag) + " does not decompress");
        return raw;
    };
    // Counts are read from each section's first bytes, before its checksum can be: where they
    // make no sense, a section that fails its checksum is named instead (damage, not a lie).
    auto damageFirst = [&](const auto& price) {
        try {
            return price();
        } catch (const Error&) {
            for (const SectionEntry& s : sections)
                if (version >= 7 && !s.cut && !frameIntact(s.stored, s.rawSize))
                    throw Error(name + ": section " + tagName(s.tag) + " fails its checksum (damaged)");
            throw;
        }
    };
    {
        const auto raw = inflated(sections[0], damageFirst([&] { return priceCage(sections[0], name, budget); }));
        ByteReader section(raw, name + ": " + sections[0].what());
        asset.cage = decodeCage(section, &shipped.positionBits);
        shipped.cageSection = raw;
        if (section.remaining() != 0) throw Error(section.what() + ": trailing bytes");
    }
    int mapResolution = 0;
    const std::vector<std::uint64_t> most =
        damageFirst([&] { return priceMaps(sections, asset.cage, name, budget, mapResolution); });
    if (priced) priced({.cage = asset.cage, .decodeTriangles = asset.decodeTriangles, .mapResolution = mapResolution});

    for (size_t k = 1; k < sections.size(); ++k) {
        const Tag& tag = sections[k].tag;
        const auto raw = inflated(sections[k], most[k]);
        ByteReader section(raw, name + ": " + sections[k].what());
        if (const kinds::MapKindInfo* geometric = geometricSection(tag)) {
            std::vector<ChannelQuantisation> coded;
            int levels = 0;
            asset.maps.values(geometric->kind) =
                readMaps(section, asset.cage, geometric->channels,
                         version >= 11   ? NodeStream::LevelBlocks
                         : version == 10 ? NodeStream::LevelBlocksOneStep
                                         : NodeStream::TileVarints,
                         asset.maps.layout, sections[k].cut ? NodeEnding::Prefix : NodeEnding::Whole, coded, levels);
            if (geometric->kind == MapKind::Displacement && asset.maps.hasDisplacement())
                asset.heightsCoding = coded.front();
            if (sections[k].cut && asset.maps.has(geometric->kind))
                keepTheWholeLattice(asset.cage, asset.maps, *geometric, levels);
        } else if (tag == kAtlasUvs) {
            if (asset.maps.appearanceLayout.resolution != 0) throw Error(name + ": section AUVS after the appearance");
            if (version == 4)
                throw Error(name +
                            ": .subd version 4 atlas coordinates (a development format); simplify the asset again");
            asset.maps.appearanceAtlas = readAtlasUvs(section, asset.cage);
        } else if (tag == kBaseColor) {
            shipped.images.push_back(readAppearance(section, asset.cage, AppearanceImage::BaseColor, asset.maps));
        } else if (tag == kMetallicRoughness) {
            shipped.images.push_back(
                readAppearance(section, asset.cage, AppearanceImage::MetallicRoughness, asset.maps));
        } else if (tag == kNormalTexture) {
            if (!asset.maps.appearanceAtlas.present())
                throw Error(name + ": section " + tagName(tag) + " without AUVS");
            shipped.images.push_back(readAppearance(section, asset.cage, AppearanceImage::NormalTexture, asset.maps));
        } else {
            shipped.images.push_back(readAppearance(section, asset.cage, AppearanceImage::Emissive, asset.maps));
        }
        if (!sections[k].cut && section.remaining() != 0) throw Error(section.what() + ": trailing bytes");
    }
    const bool appearance = std::any_of(shipped.images.begin(), shipped.images.end(), [](const ShippedImage& image) {
        return image.which == AppearanceImage::BaseColor || image.which == AppearanceImage::MetallicRoughness;
    });
    if (asset.maps.appearanceAtlas.present() && !appearance) {
        if (!prefix) throw Error(name + ": atlas coordinates without an appearance");
        asset.maps.appearanceAtlas = {};  // the images lie beyond the prefix
        asset.maps.appearanceLayout = {};
    }
    if (prefix && !asset.maps.hasDisplacement()) flags &= ~kLimitShadingFlag;
    if (flags & kLimitShadingFlag) {
        if (!asset.maps.hasDisplacement()) throw Error(name + ": limit shading flagged without a displacement");
        asset.maps.shadingNormal = surface::ShadingNormal::Limit;
    }
    return shipped;
}

SubdAsset decodeSubd(std::span<const unsigned char> bytes, const std::string& name, DecodeBudget* budget,
                     const std::function<void(const SubdOutline&)>& priced, SubdEnding ending) {
    ShippedSubd shipped = readShippedSubd(bytes, name, budget, priced, ending);
    for (const ShippedImage& image : shipped.images)
        decodeAppearance(image, name + ": " + tagName(tagOf(image.which)) + " section", shipped.asset.maps);
    return std::move(shipped.asset);
}

io::WrittenFile writeSubd(const std::filesystem::path& path, const SubdAsset& asset, const SubdPrecision& precision) {
    return io::writeBytes(path, encodeSubd(asset, precision));
}

std::size_t cageEnd(std::span<const unsigned char> bytes, const std::string& name) {
    const ShippedSubd shipped = readShippedSubd(bytes, name);
    std::uint16_t version;
    std::memcpy(&version, bytes.data() + 4, sizeof version);
    if (version < 10) return 0;
    std::size_t end = bytes.size() - 8;  // the trailer's hash
    for (size_t k = 1; k < shipped.sectionBytes.size(); ++k) end -= shipped.sectionBytes[k].second;
    return end;
}

SubdAsset readSubd(const std::filesystem::path& path, DecodeBudget* budget,
                   const std::function<void(const SubdOutline&)>& priced, std::size_t firstBytes) {
    const std::string bytes = io::readInputFile(path);
    const bool prefix = firstBytes < bytes.size();
    return decodeSubd({reinterpret_cast<const unsigned char*>(bytes.data()), prefix ? firstBytes : bytes.size()},
                      path.string(), budget, priced, prefix ? SubdEnding::Prefix : SubdEnding::Whole);
}

}  // namespace subdfit::codec
