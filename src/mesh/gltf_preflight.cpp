#include "mesh/gltf_preflight.h"

#include <array>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <string_view>

#include <nlohmann/json.hpp>

#include "util/error.h"

namespace subdfit::mesh::gltf {

namespace {

using nlohmann::json;

constexpr std::string_view kDraco = "KHR_draco_mesh_compression";

bool isObject(const json& doc, const char* key) { return doc.contains(key) && doc[key].is_object(); }
bool isArray(const json& doc, const char* key) { return doc.contains(key) && doc[key].is_array(); }

// glTF's offsets, lengths, strides and counts are integers >= 0.
void checkUnsignedFields(const json& doc, const std::string& path) {
    struct Fields {
        const char* array;
        std::array<const char*, 3> keys;  // nullptr-padded
    };
    static constexpr Fields fields[] = {
        {"buffers", {"byteLength"}},
        {"bufferViews", {"byteOffset", "byteLength", "byteStride"}},
        {"accessors", {"byteOffset", "count"}},
    };
    for (const auto& [array, keys] : fields) {
        if (!isArray(doc, array)) continue;
        for (size_t i = 0; i < doc[array].size(); ++i) {
            const json& item = doc[array][i];
            if (!item.is_object()) continue;
            for (const char* key : keys) {
                if (!key || !item.contains(key)) continue;
                const json& value = item[key];
                const bool ok =
                    value.is_number_unsigned() || (value.is_number_float() && value.get<double>() >= 0.0 &&
                                                   value.get<double>() == double(std::uint64_t(value.get<double>())));
                if (!ok)
                    throw fileError(path, std::string(array) + "[" + std::to_string(i) + "]." + key + " is " +
                                              value.dump() + ", not an integer >= 0");
            }
        }
    }
}

void checkUris(const json& doc, const std::string& path) {
    for (const char* array : {"buffers", "images"}) {
        if (!isArray(doc, array)) continue;
        for (size_t i = 0; i < doc[array].size(); ++i) {
            const json& item = doc[array][i];
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
            if (const std::string problem = uriProblem(item["uri"].get<std::string>()); !problem.empty())
                throw fileError(path, std::string(array) + "[" + std::to_string(i) + "].uri " + problem);
        }
    }
}

// Removes `indices` from Draco primitives; true when something changed.
bool dropDracoIndices(json& doc) {
    if (!isArray(doc, "meshes")) return false;
    bool changed = false;
    for (auto& mesh : doc["meshes"]) {
        if (!mesh.is_object() || !isArray(mesh, "primitives")) continue;
        for (auto& primitive : mesh["primitives"]) {
            if (!primitive.is_object() || !isObject(primitive, "extensions")) continue;
            if (primitive["extensions"].contains(kDraco) && primitive.contains("indices")) {
                primitive.erase("indices");
                changed = true;
            }
        }
    }
    return changed;
}

// The checked JSON, rewritten; empty when nothing changed (or it does not parse).
std::string checkedJson(std::string_view text, const std::string& path) {
    json doc = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded() || !doc.is_object()) return {};
    checkUnsignedFields(doc, path);
    checkUris(doc, path);
    return dropDracoIndices(doc) ? doc.dump() : std::string();
}

uint32_t readU32(const std::string& bytes, size_t offset) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);  // GLB is little-endian, as is every target we build for
    return v;
}

void writeU32(std::string& bytes, size_t offset, uint32_t v) { std::memcpy(bytes.data() + offset, &v, 4); }

int hexValue(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    c = char(std::tolower(static_cast<unsigned char>(c)));
    return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

}  // namespace

std::string uriProblem(const std::string& uri) {
    if (uri.rfind("data:", 0) == 0) return "";
    std::string shown(1, '\'');  // appended piece by piece: GCC 12 misreads "'" + string (-Wrestrict)
    shown += uri.substr(0, 200);
    shown += '\'';
    // Percent-decoded as tinygltf will before it opens the file.
    std::string decoded;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] != '%') {
            decoded += uri[i];
            continue;
        }
        const int hi = i + 2 < uri.size() ? hexValue(uri[i + 1]) : -1, lo = hi >= 0 ? hexValue(uri[i + 2]) : -1;
        if (lo < 0) return shown + " has a bad percent-escape";
        decoded += char(hi * 16 + lo);
        i += 2;
    }
    if (decoded.empty()) return "is empty";
    if (decoded.find('\0') != std::string::npos) return shown + " holds a NUL character";
    if (decoded.front() == '/' || decoded.front() == '\\') return shown + " is an absolute path";
    const size_t colon = decoded.find(':'), slash = decoded.find('/');
    if (colon != std::string::npos && (slash == std::string::npos || colon < slash))
        return shown + " has a scheme other than data: (only relative paths are read)";
    // Normalised: a '..' that climbs above the folder leaves it, wherever it is.
    int depth = 0;
    for (size_t start = 0; start <= decoded.size();) {
        const size_t end = std::min(decoded.find_first_of("/\\", start), decoded.size());
        const std::string_view part = std::string_view(decoded).substr(start, end - start);
        if (part == "..") {
            if (--depth < 0) return shown + " leaves the glTF file's folder";
        } else if (!part.empty() && part != ".") {
            ++depth;
        }
        start = end + 1;
    }
    return "";
}

void preflight(std::string& bytes, const std::string& path) {
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (!binary) {
        if (std::string json = checkedJson(bytes, path); !json.empty()) bytes = std::move(json);
        return;
    }
    // GLB: 12-byte header (magic, version, length), then the JSON chunk (length, type, data).
    constexpr uint32_t kJsonChunk = 0x4E4F534A;
    if (bytes.size() < 20) return;
    const uint32_t length = readU32(bytes, 8), jsonLength = readU32(bytes, 12);
    if (length != bytes.size() || readU32(bytes, 16) != kJsonChunk || jsonLength > bytes.size() - 20) return;
    std::string json = checkedJson(std::string_view(bytes).substr(20, jsonLength), path);
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
