#include "export/meshopt_encoding.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <glm/common.hpp>

#include "mesh/point_welder.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

using nlohmann::json;
using namespace gltf;

template <typename T>
std::vector<T> remapped(const std::vector<T>& values, const std::vector<unsigned>& remap, std::size_t unique) {
    std::vector<T> out(unique);
    meshopt_remapVertexBuffer(out.data(), values.data(), values.size(), sizeof(T), remap.data());
    return out;
}

// One attribute stream: `stride` bytes a vertex (a multiple of 4, as the codec requires).
int addVertexStream(BinaryBuilder& binary, const std::vector<std::uint8_t>& bytes, std::size_t count, int stride) {
    std::vector<unsigned char> compressed(meshopt_encodeVertexBufferBound(count, std::size_t(stride)));
    compressed.resize(meshopt_encodeVertexBuffer(compressed.data(), compressed.size(), bytes.data(), count, std::size_t(stride)));
    if (compressed.empty()) throw Error("meshopt could not encode a vertex stream");
    return binary.addMeshoptView(compressed, count, stride, "ATTRIBUTES", kArrayBuffer);
}

std::int8_t snorm8(float v) { return std::int8_t(std::lround(std::clamp(v, -1.0f, 1.0f) * 127.0f)); }

}  // namespace

MeshoptPrimitive addMeshoptPrimitive(const GltfMesh& input, BinaryBuilder& binary, json& accessors) {
    SUBDFIT_CHECK(input.attributesConsistent());
    const std::size_t vertices = input.vertexCount(), indexCount = input.indices.size();
    std::vector<unsigned> indices(indexCount);
    meshopt_optimizeVertexCache(indices.data(), input.indices.data(), indexCount, vertices);
    std::vector<unsigned> remap(vertices);
    const std::size_t n = meshopt_optimizeVertexFetchRemap(remap.data(), indices.data(), indexCount, vertices);
    meshopt_remapIndexBuffer(indices.data(), indices.data(), indexCount, remap.data());

    MeshoptPrimitive out;
    auto add = [&](const char* name, int view, int componentType, const char* type, bool normalized) {
        json a = accessor(view, componentType, n, type);
        if (normalized) a["normalized"] = true;
        accessors.push_back(std::move(a));
        out.attributes[name] = accessors.size() - 1;
        return accessors.size() - 1;
    };

    // Positions on a grid of 2^14 - 1 steps over the largest side of the bounding box.
    // Points that coincide to rounding (a face border evaluated from both sides) quantise alike.
    const std::vector<glm::vec3> positions = mesh::coincidentPointsMerged(remapped(input.positions, remap, n));
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const float side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    constexpr int kSteps = (1 << kQuantisedPositionBits) - 1;
    const float step = side > 0.0f ? side / float(kSteps) : 1.0f;
    std::vector<std::uint8_t> bytes(n * 8, 0);
    std::array<int, 3> qLo{kSteps, kSteps, kSteps}, qHi{0, 0, 0};
    for (std::size_t v = 0; v < n; ++v)
        for (int c = 0; c < 3; ++c) {
            const int q = std::clamp(int(std::lround((positions[v][c] - lo[c]) / step)), 0, kSteps);
            const auto value = std::uint16_t(q);
            std::memcpy(bytes.data() + 8 * v + 2 * std::size_t(c), &value, 2);
            qLo[std::size_t(c)] = std::min(qLo[std::size_t(c)], q);
            qHi[std::size_t(c)] = std::max(qHi[std::size_t(c)], q);
        }
    const auto position = add("POSITION", addVertexStream(binary, bytes, n, 8), kUnsignedShort, "VEC3", false);
    accessors[position]["min"] = qLo;
    accessors[position]["max"] = qHi;
    out.translation = {lo.x, lo.y, lo.z};
    out.scale = step;

    if (input.hasNormals()) {
        const auto normals = remapped(input.normals, remap, n);
        bytes.assign(n * 4, 0);
        for (std::size_t v = 0; v < n; ++v)
            for (int c = 0; c < 3; ++c) bytes[4 * v + std::size_t(c)] = std::uint8_t(snorm8(normals[v][c]));
        add("NORMAL", addVertexStream(binary, bytes, n, 4), kByte, "VEC3", true);
    }
    if (input.hasTangents()) {
        const auto tangents = remapped(input.tangents, remap, n);
        bytes.assign(n * 4, 0);
        for (std::size_t v = 0; v < n; ++v)
            for (int c = 0; c < 4; ++c) bytes[4 * v + std::size_t(c)] = std::uint8_t(snorm8(tangents[v][c]));
        add("TANGENT", addVertexStream(binary, bytes, n, 4), kByte, "VEC4", true);
    }
    if (input.hasUvs()) {
        const auto uvs = remapped(input.uvs, remap, n);
        const bool unit = std::all_of(uvs.begin(), uvs.end(), [](const glm::vec2& uv) {
            return uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f;
        });
        if (unit) {
            bytes.assign(n * 4, 0);
            for (std::size_t v = 0; v < n; ++v)
                for (int c = 0; c < 2; ++c) {
                    const auto value = std::uint16_t(std::lround(uvs[v][c] * 65535.0f));
                    std::memcpy(bytes.data() + 4 * v + 2 * std::size_t(c), &value, 2);
                }
            add("TEXCOORD_0", addVertexStream(binary, bytes, n, 4), kUnsignedShort, "VEC2", true);
        } else {
            bytes.assign(n * 8, 0);
            std::memcpy(bytes.data(), uvs.data(), n * 8);
            add("TEXCOORD_0", addVertexStream(binary, bytes, n, 8), kFloat, "VEC2", false);
        }
    }

    const bool shortIndices = n <= 65536;
    std::vector<unsigned char> compressed(meshopt_encodeIndexBufferBound(indexCount, n));
    compressed.resize(meshopt_encodeIndexBuffer(compressed.data(), compressed.size(), indices.data(), indexCount));
    if (compressed.empty()) throw Error("meshopt could not encode the indices");
    const int view = binary.addMeshoptView(compressed, indexCount, shortIndices ? 2 : 4, "TRIANGLES", kElementArrayBuffer);
    accessors.push_back(accessor(view, shortIndices ? kUnsignedShort : kUnsignedInt, indexCount, "SCALAR"));
    out.indices = int(accessors.size()) - 1;
    return out;
}

}  // namespace subdfit::exporter
