#include "mesh/gltf_draco_indices.h"

#include <cstdint>
#include <cstring>
#include <string_view>

#include <nlohmann/json.hpp>

namespace subdfit::mesh::gltf {

namespace {

constexpr std::string_view kDraco = "KHR_draco_mesh_compression";

// The JSON with `indices` removed from Draco primitives; empty when nothing changed.
std::string rewrittenJson(std::string_view text) {
    if (text.find(kDraco) == std::string_view::npos) return {};
    nlohmann::json doc = nlohmann::json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("meshes") || !doc["meshes"].is_array()) return {};
    bool changed = false;
    for (auto& mesh : doc["meshes"]) {
        if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
        for (auto& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !primitive.contains("extensions")) continue;
            const auto& extensions = primitive["extensions"];
            if (extensions.is_object() && extensions.contains(kDraco) && primitive.contains("indices")) {
                primitive.erase("indices");
                changed = true;
            }
        }
    }
    return changed ? doc.dump() : std::string();
}

uint32_t readU32(const std::string& bytes, size_t offset) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);  // GLB is little-endian, as is every target we build for
    return v;
}

void writeU32(std::string& bytes, size_t offset, uint32_t v) { std::memcpy(bytes.data() + offset, &v, 4); }

}  // namespace

void dropDracoPrimitiveIndices(std::string& bytes) {
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (!binary) {
        if (std::string json = rewrittenJson(bytes); !json.empty()) bytes = std::move(json);
        return;
    }
    // GLB: 12-byte header (magic, version, length), then the JSON chunk (length, type, data).
    constexpr uint32_t kJsonChunk = 0x4E4F534A;
    if (bytes.size() < 20) return;
    const uint32_t length = readU32(bytes, 8), jsonLength = readU32(bytes, 12);
    if (length != bytes.size() || readU32(bytes, 16) != kJsonChunk || jsonLength > bytes.size() - 20) return;
    std::string json = rewrittenJson(std::string_view(bytes).substr(20, jsonLength));
    if (json.empty()) return;
    json.append((4 - json.size() % 4) % 4, ' ');  // chunks stay 4-byte aligned
    const uint64_t newLength = uint64_t(bytes.size()) - jsonLength + json.size();
    if (newLength > UINT32_MAX) return;
    std::string out = bytes.substr(0, 20) + json + bytes.substr(20 + size_t(jsonLength));
    writeU32(out, 8, uint32_t(newLength));
    writeU32(out, 12, uint32_t(json.size()));
    bytes = std::move(out);
}

}  // namespace subdfit::mesh::gltf
