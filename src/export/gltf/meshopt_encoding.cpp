#include "export/gltf/meshopt_encoding.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string_view>
#include <vector>

#include <glm/common.hpp>

#include "mesh/point_welder.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

using nlohmann::json;
using namespace gltf;

// One attribute as it ships: `stride` bytes a vertex (a multiple of 4, as the codec requires).
struct Stream {
    const char* name;
    std::vector<std::uint8_t> bytes;
    int stride, componentType;
    const char* type;
    bool normalized;
    const char* filter = nullptr;  // EXT_meshopt_compression's, undone by the loader's decoder
};

// Unit vectors (w, a tangent's handedness, kept) as normalised bytes: compressed, in the
// octahedral filter (two 8-bit coordinates on the octahedron, which the codec packs far better
// than x, y, z); plain, as x, y, z (and w) themselves, 4 bytes a vertex as glTF aligns them.
template <typename Vec>
Stream unitVectorStream(const char* name, const std::vector<Vec>& values, const char* type, bool compressed) {
    std::vector<glm::vec4> unit(values.size(), glm::vec4(0.0f));
    for (std::size_t v = 0; v < values.size(); ++v)
        for (int c = 0; c < Vec::length(); ++c) unit[v][c] = values[v][c];
    Stream out{name,
               std::vector<std::uint8_t>(values.size() * 4, 0),
               4,
               kByte,
               type,
               true,
               compressed ? "OCTAHEDRAL" : nullptr};
    if (compressed) {
        meshopt_encodeFilterOct(out.bytes.data(), unit.size(), 4, 8, &unit[0].x);
        return out;
    }
    for (std::size_t v = 0; v < unit.size(); ++v)
        for (int c = 0; c < 4; ++c)
            out.bytes[4 * v + std::size_t(c)] =
                std::uint8_t(std::int8_t(std::lround(std::clamp(unit[v][c], -1.0f, 1.0f) * 127.0f)));
    return out;
}

Stream uvStream(const std::vector<glm::vec2>& uvs) {
    const std::size_t n = uvs.size();
    const bool unit = std::all_of(uvs.begin(), uvs.end(), [](const glm::vec2& uv) {
        return uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f;
    });
    if (!unit) {
        Stream out{"TEXCOORD_0", std::vector<std::uint8_t>(n * 8), 8, kFloat, "VEC2", false};
        std::memcpy(out.bytes.data(), uvs.data(), n * 8);
        return out;
    }
    Stream out{"TEXCOORD_0", std::vector<std::uint8_t>(n * 4), 4, kUnsignedShort, "VEC2", true};
    for (std::size_t v = 0; v < n; ++v)
        for (int c = 0; c < 2; ++c) {
            const auto value = std::uint16_t(std::lround(uvs[v][c] * 65535.0f));
            std::memcpy(out.bytes.data() + 4 * v + 2 * std::size_t(c), &value, 2);
        }
    return out;
}

}  // namespace

MeshoptPrimitive addQuantizedPrimitive(const GltfMesh& input, BinaryBuilder& binary, json& accessors, bool compressed) {
    SUBDFIT_CHECK(input.attributesConsistent());
    const std::size_t vertices = input.vertexCount(), indexCount = input.indices.size();
    MeshoptPrimitive out;

    // Positions on a grid of 2^14 - 1 steps over the largest side of the bounding box.
    // Points that coincide to rounding (a face border evaluated from both sides) quantise alike.
    const std::vector<glm::vec3> positions = mesh::coincidentPointsMerged(input.positions);
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    constexpr int kSteps = (1 << kQuantisedPositionBits) - 1;
    const float step = side > 0.0f ? side / float(kSteps) : 1.0f;
    std::vector<Stream> streams{
        {"POSITION", std::vector<std::uint8_t>(vertices * 8, 0), 8, kUnsignedShort, "VEC3", false}};
    for (std::size_t v = 0; v < vertices; ++v)
        for (int c = 0; c < 3; ++c) {
            const auto q = std::uint16_t(std::clamp(int(std::lround((positions[v][c] - lo[c]) / step)), 0, kSteps));
            std::memcpy(streams[0].bytes.data() + 8 * v + 2 * std::size_t(c), &q, 2);
        }
    out.translation = {lo.x, lo.y, lo.z};
    out.scale = step;
    if (input.hasNormals()) streams.push_back(unitVectorStream("NORMAL", input.normals, "VEC3", compressed));
    if (input.hasTangents()) streams.push_back(unitVectorStream("TANGENT", input.tangents, "VEC4", compressed));
    if (input.hasUvs()) streams.push_back(uvStream(input.uvs));

    // Vertices that ship alike (a face border's both sides, where no attribute tells them
    // apart) are one; then the triangles are ordered for the vertex cache, the vertices for fetching.
    std::vector<meshopt_Stream> views;
    for (const Stream& s : streams) views.push_back({s.bytes.data(), std::size_t(s.stride), std::size_t(s.stride)});
    std::vector<unsigned> remap(vertices);
    std::size_t n = meshopt_generateVertexRemapMulti(remap.data(), input.indices.data(), indexCount, vertices,
                                                     views.data(), views.size());
    std::vector<unsigned> indices(indexCount);
    meshopt_remapIndexBuffer(indices.data(), input.indices.data(), indexCount, remap.data());
    meshopt_optimizeVertexCache(indices.data(), indices.data(), indexCount, n);
    for (Stream& s : streams) {
        std::vector<std::uint8_t> welded(n * std::size_t(s.stride));
        meshopt_remapVertexBuffer(welded.data(), s.bytes.data(), vertices, std::size_t(s.stride), remap.data());
        s.bytes = std::move(welded);
    }
    std::vector<unsigned> fetch(n);
    n = meshopt_optimizeVertexFetchRemap(fetch.data(), indices.data(), indexCount, n);
    meshopt_remapIndexBuffer(indices.data(), indices.data(), indexCount, fetch.data());

    for (Stream& s : streams) {
        const auto stride = std::size_t(s.stride);
        std::vector<std::uint8_t> ordered(n * stride);
        meshopt_remapVertexBuffer(ordered.data(), s.bytes.data(), s.bytes.size() / stride, stride, fetch.data());
        int view = -1;
        if (compressed) {
            std::vector<unsigned char> packed(meshopt_encodeVertexBufferBound(n, stride));
            packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), ordered.data(), n, stride));
            if (packed.empty()) throw Error("meshopt could not encode a vertex stream");
            view = binary.addMeshoptView(packed, n, s.stride, "ATTRIBUTES", kArrayBuffer, s.filter);
        } else {
            view = binary.addView(ordered, kArrayBuffer, s.stride);
        }
        json a = accessor(view, s.componentType, n, s.type);
        if (s.normalized) a["normalized"] = true;
        if (std::string_view(s.name) == "POSITION") {
            std::array<int, 3> qLo{kSteps, kSteps, kSteps}, qHi{0, 0, 0};
            for (std::size_t v = 0; v < n; ++v)
                for (std::size_t c = 0; c < 3; ++c) {
                    std::uint16_t q = 0;
                    std::memcpy(&q, ordered.data() + 8 * v + 2 * c, 2);
                    qLo[c] = std::min(qLo[c], int(q));
                    qHi[c] = std::max(qHi[c], int(q));
                }
            a["min"] = qLo;
            a["max"] = qHi;
        }
        accessors.push_back(std::move(a));
        out.attributes[s.name] = accessors.size() - 1;
    }

    const bool shortIndices = n <= 65536;
    int view = -1;
    if (compressed) {
        std::vector<unsigned char> packed(meshopt_encodeIndexBufferBound(indexCount, n));
        packed.resize(meshopt_encodeIndexBuffer(packed.data(), packed.size(), indices.data(), indexCount));
        if (packed.empty()) throw Error("meshopt could not encode the indices");
        view = binary.addMeshoptView(packed, indexCount, shortIndices ? 2 : 4, "TRIANGLES", kElementArrayBuffer);
    } else if (shortIndices) {
        view = binary.addArray(std::vector<std::uint16_t>(indices.begin(), indices.end()), kElementArrayBuffer);
    } else {
        view = binary.addArray(indices, kElementArrayBuffer);
    }
    accessors.push_back(accessor(view, shortIndices ? kUnsignedShort : kUnsignedInt, indexCount, "SCALAR"));
    out.indices = int(accessors.size()) - 1;
    return out;
}

}  // namespace subdfit::exporter
