#include "export/subd_format.h"

#include <zstd.h>

#include <glm/common.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "export/byte_stream.h"
#include "export/node_coding.h"
#include "io/input_file.h"
#include "mesh/input_limits.h"
#include "mesh/mesh_validation.h"
#include "surface/texel_layout.h"
#include "util/hash.h"

namespace subdfit::exporter {
namespace {

using Tag = std::array<char, 4>;
constexpr Tag kCage{'C', 'A', 'G', 'E'}, kDisplacement{'D', 'I', 'S', 'P'}, kNormal{'N', 'O', 'R', 'M'};
constexpr char kMagic[4] = {'S', 'U', 'B', 'D'};
constexpr int kZstdLevel = 19;  // the asset is written once and shipped many times
constexpr std::uint32_t kMaxRawSection = 1u << 30;

std::string tagName(const Tag& tag) { return std::string(tag.begin(), tag.end()); }

// The cage's bounding cube: origin and edge length (1 for a single point).
std::pair<glm::vec3, float> boundingCube(const std::vector<glm::vec3>& positions) {
    glm::vec3 low(std::numeric_limits<float>::max()), high(-std::numeric_limits<float>::max());
    for (const auto& p : positions) {
        low = glm::min(low, p);
        high = glm::max(high, p);
    }
    const float extent = std::max({high.x - low.x, high.y - low.y, high.z - low.z});
    return {low, extent > 0.0f ? extent : 1.0f};
}

float levels(int bits) { return float((1u << bits) - 1u); }

void writeCage(const mesh::PolygonMesh& cage, int bits, ByteWriter& out) {
    out.putVarint(std::uint64_t(cage.vertexCount()));
    out.putVarint(std::uint64_t(cage.faceCount()));
    const auto [origin, extent] = boundingCube(cage.positions);
    for (float c : {origin.x, origin.y, origin.z, extent}) out.put<float>(c);
    out.put<std::uint8_t>(std::uint8_t(bits));
    for (int axis = 0; axis < 3; ++axis)
        for (const auto& p : cage.positions)
            out.put<std::uint16_t>(std::uint16_t(std::lround(std::clamp((p[axis] - origin[axis]) / extent, 0.0f, 1.0f) * levels(bits))));
    for (int size : cage.faceSizes) out.putVarint(std::uint64_t(size));
    int previous = 0;
    for (int index : cage.faceIndices) {
        out.putSigned(std::int64_t(index) - previous);
        previous = index;
    }
    const auto& t = cage.tags;
    for (int value : {int(t.boundary), t.faceVaryingBoundary, int(t.creaseMethod), int(t.triangles)})
        out.put<std::uint8_t>(std::uint8_t(value));
    out.putVarint(t.creases.size());
    for (const auto& c : t.creases) {
        out.putVarint(std::uint64_t(c.v0));
        out.putVarint(std::uint64_t(c.v1));
        out.put<float>(c.sharpness);
    }
    out.putVarint(t.corners.size());
    for (const auto& c : t.corners) {
        out.putVarint(std::uint64_t(c.vertex));
        out.put<float>(c.sharpness);
    }
    out.putVarint(t.holes.size());
    for (int face : t.holes) out.putVarint(std::uint64_t(face));
}

int readIndex(ByteReader& in, std::uint64_t limit, const char* what) {
    const std::uint64_t v = in.getVarint();
    if (v >= limit) throw Error(in.what() + ": " + what + " " + std::to_string(v) + " out of range");
    return int(v);
}

mesh::PolygonMesh readCage(ByteReader& in, const std::string& name) {
    mesh::PolygonMesh cage;
    cage.sourcePath = name;
    const std::size_t vertices = in.getCount(6, "vertex"), faces = in.getCount(1, "face");
    if (vertices > std::size_t(mesh::kMaxVertices) || faces > std::size_t(mesh::kMaxTriangles))
        throw Error(in.what() + ": more vertices or faces than subdfit reads");
    glm::vec3 origin;
    for (int axis = 0; axis < 3; ++axis) origin[axis] = in.get<float>();
    const float extent = in.get<float>();
    const int bits = in.get<std::uint8_t>();
    if (bits < 1 || bits > 16 || !(extent > 0.0f) || !std::isfinite(extent) || !std::isfinite(origin.x + origin.y + origin.z))
        throw Error(in.what() + ": bad position quantisation");
    cage.positions.resize(vertices);
    for (int axis = 0; axis < 3; ++axis)
        for (auto& p : cage.positions) p[axis] = origin[axis] + float(in.get<std::uint16_t>()) / levels(bits) * extent;
    cage.faceSizes.resize(faces);
    std::uint64_t corners = 0;
    for (int& size : cage.faceSizes) {
        size = readIndex(in, std::uint64_t(mesh::kMaxCageFaceSize) + 1, "face size");
        corners += std::uint64_t(size);
    }
    if (corners > in.remaining()) throw Error(in.what() + ": truncated face indices");
    cage.faceIndices.resize(corners);
    std::int64_t previous = 0;
    for (int& index : cage.faceIndices) {
        previous += in.getSigned();
        if (previous < 0 || previous >= std::int64_t(vertices)) throw Error(in.what() + ": face index out of range");
        index = int(previous);
    }
    auto& t = cage.tags;
    const int boundary = in.get<std::uint8_t>(), faceVarying = in.get<std::uint8_t>(), method = in.get<std::uint8_t>(),
              triangles = in.get<std::uint8_t>();
    if (boundary > 2 || faceVarying > 5 || method > 1 || triangles > 1) throw Error(in.what() + ": unknown subdivision rule");
    t.boundary = mesh::BoundaryInterpolation(boundary);
    t.faceVaryingBoundary = faceVarying;
    t.creaseMethod = mesh::CreaseMethod(method);
    t.triangles = mesh::TriangleSubdivision(triangles);
    t.hasBoundary = t.hasFaceVaryingBoundary = t.hasCreaseMethod = t.hasTriangles = true;
    t.creases.resize(in.getCount(6, "crease"));
    for (auto& c : t.creases) {
        c.v0 = readIndex(in, vertices, "crease vertex");
        c.v1 = readIndex(in, vertices, "crease vertex");
        c.sharpness = in.get<float>();
    }
    t.corners.resize(in.getCount(5, "corner"));
    for (auto& c : t.corners) {
        c.vertex = readIndex(in, vertices, "corner vertex");
        c.sharpness = in.get<float>();
    }
    t.holes.resize(in.getCount(1, "hole"));
    for (int& face : t.holes) face = readIndex(in, faces, "hole face");
    mesh::validateMesh(cage);
    return cage;
}

void writeMaps(const surface::SurfaceMaps& maps, const std::vector<float>& values, int channels, int bits, ByteWriter& out) {
    out.putVarint(std::uint64_t(maps.layout.resolution));
    out.putVarint(std::uint64_t(maps.layout.nodeCount));
    std::vector<ChannelQuantisation> q;
    for (int c = 0; c < channels; ++c) {
        q.push_back(quantisationFor(values, channels, c, bits));
        out.put<float>(q.back().center);
        out.put<float>(q.back().step);
    }
    for (int c = 0; c < channels; ++c) encodeNodes(maps.layout, values, channels, c, q[size_t(c)], out);
}

std::vector<float> readMaps(ByteReader& in, const mesh::PolygonMesh& cage, int channels, surface::TexelLayout& layout) {
    const int resolution = readIndex(in, 65, "map resolution");
    if (resolution < 1) throw Error(in.what() + ": map resolution 0");
    if (layout.resolution == 0) layout = surface::buildTexelLayout(cage, resolution);
    if (layout.resolution != resolution) throw Error(in.what() + ": the maps disagree on their resolution");
    if (in.getVarint() != std::uint64_t(layout.nodeCount))
        throw Error(in.what() + ": node count does not match the cage's texel layout");
    std::vector<ChannelQuantisation> q(static_cast<size_t>(channels));
    for (auto& channel : q) {
        channel.center = in.get<float>();
        channel.step = in.get<float>();
        if (!std::isfinite(channel.center) || !(channel.step > 0.0f) || !std::isfinite(channel.step))
            throw Error(in.what() + ": bad quantisation");
    }
    std::vector<float> values(size_t(layout.nodeCount) * size_t(channels));
    for (int c = 0; c < channels; ++c) decodeNodes(layout, values, channels, c, q[size_t(c)], in);
    return values;
}

void putSection(ByteWriter& file, const Tag& tag, const std::vector<unsigned char>& raw) {
    std::vector<unsigned char> stored(ZSTD_compressBound(raw.size()));
    const std::size_t size = ZSTD_compress(stored.data(), stored.size(), raw.data(), raw.size(), kZstdLevel);
    if (ZSTD_isError(size)) throw Error(std::string("zstd: ") + ZSTD_getErrorName(size));
    file.putBytes({reinterpret_cast<const unsigned char*>(tag.data()), 4});
    file.put<std::uint32_t>(std::uint32_t(size));
    file.put<std::uint32_t>(std::uint32_t(raw.size()));
    file.putBytes({stored.data(), size});
}

}  // namespace

mesh::PolygonMesh quantisedCage(const mesh::PolygonMesh& cage, int positionBits) {
    ByteWriter out;
    writeCage(cage, positionBits, out);
    ByteReader in(out.bytes(), "quantised cage");
    mesh::PolygonMesh result = readCage(in, cage.sourcePath);
    result.tags = cage.tags;  // as given, passthrough tags and which were explicit included
    return result;
}

SubdAsset shippableAsset(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps, int positionBits) {
    SubdAsset asset{.cage = cage, .maps = {}};
    const int T = maps.layout.resolution;
    if (T == 0 || (!maps.hasDisplacement() && !maps.hasNormal())) return asset;
    surface::SurfaceMaps& out = asset.maps;
    out.layout = surface::buildTexelLayout(quantisedCage(cage, positionBits), T);
    if (out.layout.faceNodes == maps.layout.faceNodes) {
        out = maps;
        return asset;
    }
    auto carry = [&](const std::vector<float>& from, int channels) {
        std::vector<float> to(size_t(out.layout.nodeCount) * size_t(channels), 0.0f);
        for (int face = 0; face < out.layout.ptexFaceCount; ++face)
            for (int j = 0; j <= T; ++j)
                for (int i = 0; i <= T; ++i)
                    for (int c = 0; c < channels; ++c)
                        to[size_t(out.layout.node(face, i, j)) * size_t(channels) + size_t(c)] =
                            from[size_t(maps.layout.node(face, i, j)) * size_t(channels) + size_t(c)];
        return to;
    };
    if (maps.hasDisplacement()) out.displacement = carry(maps.displacement, 1);
    if (maps.hasNormal()) out.normal = carry(maps.normal, 2);
    return asset;
}

std::vector<unsigned char> encodeSubd(const SubdAsset& asset, const SubdPrecision& precision) {
    SUBDFIT_CHECK(precision.positionBits >= 8 && precision.positionBits <= 16);
    std::vector<std::pair<Tag, std::vector<unsigned char>>> sections;
    ByteWriter cage;
    writeCage(asset.cage, precision.positionBits, cage);
    sections.emplace_back(kCage, std::move(cage.bytes()));
    const auto& maps = asset.maps;
    if (maps.layout.resolution > 0 && maps.hasDisplacement()) {
        ByteWriter section;
        writeMaps(maps, maps.displacement, 1, precision.displacementBits, section);
        sections.emplace_back(kDisplacement, std::move(section.bytes()));
    }
    if (maps.layout.resolution > 0 && maps.hasNormal()) {
        ByteWriter section;
        writeMaps(maps, maps.normal, 2, precision.normalBits, section);
        sections.emplace_back(kNormal, std::move(section.bytes()));
    }
    ByteWriter file;
    file.putBytes({reinterpret_cast<const unsigned char*>(kMagic), 4});
    file.put<std::uint16_t>(kSubdVersion);
    file.put<std::uint16_t>(0);
    file.put<std::uint32_t>(std::uint32_t(sections.size()));
    for (const auto& [tag, raw] : sections) putSection(file, tag, raw);
    const auto& bytes = file.bytes();
    file.put<std::uint64_t>(hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    return std::move(file.bytes());
}

SubdAsset decodeSubd(std::span<const unsigned char> bytes, const std::string& name) {
    if (bytes.size() < 4 || std::memcmp(bytes.data(), kMagic, 4) != 0) throw Error(name + ": not a .subd file");
    if (bytes.size() < 20) throw Error(name + ": truncated");
    ByteReader header(bytes, name);
    header.take(4);
    const auto version = header.get<std::uint16_t>();
    if (version != kSubdVersion)
        throw Error(name + ": .subd version " + std::to_string(version) + ", this subdfit reads version " +
                    std::to_string(kSubdVersion));
    const auto body = bytes.first(bytes.size() - 8);
    std::uint64_t stored;
    std::memcpy(&stored, bytes.data() + body.size(), 8);
    if (hash64({reinterpret_cast<const char*>(body.data()), body.size()}) != stored)
        throw Error(name + ": checksum mismatch (damaged or truncated)");
    ByteReader in(body, name);
    in.take(6);
    if (in.get<std::uint16_t>() != 0) throw Error(name + ": unknown flags");
    const auto count = in.get<std::uint32_t>();
    if (count < 1 || count > 3) throw Error(name + ": " + std::to_string(count) + " sections");

    SubdAsset asset;
    std::vector<Tag> seen;
    for (std::uint32_t k = 0; k < count; ++k) {
        Tag tag;
        std::memcpy(tag.data(), in.take(4).data(), 4);
        const auto storedSize = in.get<std::uint32_t>(), rawSize = in.get<std::uint32_t>();
        if (rawSize > kMaxRawSection) throw Error(name + ": section " + tagName(tag) + " too large");
        const auto stored = in.take(storedSize);
        if (ZSTD_getFrameContentSize(stored.data(), stored.size()) != rawSize)
            throw Error(name + ": section " + tagName(tag) + " does not decompress to its stated size");
        std::vector<unsigned char> raw(rawSize);
        const std::size_t got = ZSTD_decompress(raw.data(), raw.size(), stored.data(), stored.size());
        if (ZSTD_isError(got) || got != rawSize) throw Error(name + ": section " + tagName(tag) + " does not decompress");
        ByteReader section(raw, name + ": " + tagName(tag) + " section");
        const bool first = k == 0;
        if (first != (tag == kCage) || std::find(seen.begin(), seen.end(), tag) != seen.end())
            throw Error(name + ": section " + tagName(tag) + " out of place");
        seen.push_back(tag);
        if (tag == kCage) asset.cage = readCage(section, name);
        else if (tag == kDisplacement) asset.maps.displacement = readMaps(section, asset.cage, 1, asset.maps.layout);
        else if (tag == kNormal) asset.maps.normal = readMaps(section, asset.cage, 2, asset.maps.layout);
        else throw Error(name + ": unknown section " + tagName(tag));
        if (section.remaining() != 0) throw Error(section.what() + ": trailing bytes");
    }
    if (in.remaining() != 0) throw Error(name + ": trailing bytes after the sections");
    return asset;
}

WrittenFile writeSubd(const std::filesystem::path& path, const SubdAsset& asset, const SubdPrecision& precision) {
    return writeBytes(path, encodeSubd(asset, precision));
}

SubdAsset readSubd(const std::filesystem::path& path) {
    const std::string bytes = io::readInputFile(path);
    return decodeSubd({reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size()}, path.string());
}

}  // namespace subdfit::exporter
