#include "mesh/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <string_view>

#include <nlohmann/json.hpp>

#include "util/checked_size.h"
#include "util/error.h"

namespace subdfit::mesh::gltf {
namespace {

using nlohmann::json;

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr std::uint32_t kJsonChunk = 0x4E4F534A, kBinChunk = 0x004E4942;
// What the decoded bufferViews of one file may take together: as much as the largest input a
// reader accepts.
constexpr std::uint64_t kMaxDecodedBytes = std::uint64_t(1) << 31;
// meshoptimizer's codecs store at least 2 bits for every 16 decoded bytes (a vertex block of
// zeros); a view declaring more than this many times its compressed bytes cannot be whole, and
// is refused before its buffer is allocated.
constexpr std::uint64_t kMaxExpansion = 256;

std::uint32_t readU32(std::string_view bytes, size_t offset) {
    std::uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);  // GLB is little-endian, as every target we build for
    return v;
}

void appendU32(std::string& out, std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

bool usesMeshopt(const json& doc) {
    for (const char* list : {"extensionsUsed", "extensionsRequired"})
        if (doc.contains(list) && doc[list].is_array())
            for (const auto& name : doc[list])
                if (name == kMeshopt) return true;
    return false;
}

std::uint64_t unsignedField(const json& object, const char* key, const std::string& where) {
    if (!object.contains(key) || !object[key].is_number_unsigned())
        throw Error(where + "." + key + " is missing or not an integer >= 0");
    return object[key].get<std::uint64_t>();
}

// One compressed bufferView decoded: `count` elements of `byteStride` bytes, at most `budget`
// bytes.
std::string decodeView(const json& ext, std::string_view bin, std::uint64_t budget, const std::string& where) {
    const std::uint64_t offset = unsignedField(ext, "byteOffset", where),
                        length = unsignedField(ext, "byteLength", where),
                        stride = unsignedField(ext, "byteStride", where), count = unsignedField(ext, "count", where);
    if (unsignedField(ext, "buffer", where) != 0)
        throw Error(where + " is compressed in a buffer other than the GLB's binary chunk, which is not read");
    if (offset > bin.size() || length > bin.size() - offset) throw Error(where + " lies outside the binary chunk");
    if (stride == 0 || stride > 256 || productExceeds(count, stride, std::min(budget, kMaxExpansion * length + 1024)))
        throw Error(where + " has an impossible size (" + std::to_string(count) + " elements of " +
                    std::to_string(stride) + " bytes from " + std::to_string(length) + " compressed bytes)");
    const std::string mode = ext.value("mode", ""), filter = ext.value("filter", "NONE");
    std::string out(size_t(count * stride), '\0');
    const auto* source = reinterpret_cast<const unsigned char*>(bin.data() + offset);
    int status = -1;
    if (mode == "ATTRIBUTES" && stride % 4 == 0)
        status = meshopt_decodeVertexBuffer(out.data(), size_t(count), size_t(stride), source, size_t(length));
    else if (mode == "TRIANGLES" && (stride == 2 || stride == 4) && count % 3 == 0)
        status = meshopt_decodeIndexBuffer(out.data(), size_t(count), size_t(stride), source, size_t(length));
    else if (mode == "INDICES" && (stride == 2 || stride == 4))
        status = meshopt_decodeIndexSequence(out.data(), size_t(count), size_t(stride), source, size_t(length));
    else throw Error(where + " has mode '" + mode + "' with byteStride " + std::to_string(stride));
    if (status != 0) throw Error(where + " does not decode (damaged, or a newer meshopt encoding)");
    if (filter == "OCTAHEDRAL" && (stride == 4 || stride == 8))
        meshopt_decodeFilterOct(out.data(), size_t(count), size_t(stride));
    else if (filter == "QUATERNION" && stride == 8) meshopt_decodeFilterQuat(out.data(), size_t(count), size_t(stride));
    else if (filter == "EXPONENTIAL" && stride % 4 == 0)
        meshopt_decodeFilterExp(out.data(), size_t(count), size_t(stride));
    else if (filter != "NONE")
        throw Error(where + " has filter '" + filter + "' with byteStride " + std::to_string(stride));
    return out;
}

}  // namespace

void expandMeshopt(std::string& bytes, const std::string& path) {
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (!binary) {
        const json doc = json::parse(bytes, nullptr, /*allow_exceptions=*/false);
        if (!doc.is_discarded() && doc.is_object() && usesMeshopt(doc))
            throw fileError(path, std::string(kMeshopt) + " is read from .glb files only");
        return;
    }
    // GLB: 12-byte header, the JSON chunk, then (optionally) the binary chunk; malformed
    // containers are left for tinygltf to report.
    if (bytes.size() < 20 || readU32(bytes, 8) != bytes.size() || readU32(bytes, 16) != kJsonChunk) return;
    const std::uint32_t jsonLength = readU32(bytes, 12);
    if (jsonLength > bytes.size() - 20) return;
    json doc = json::parse(bytes.begin() + 20, bytes.begin() + 20 + jsonLength, nullptr, /*allow_exceptions=*/false);
    if (doc.is_discarded() || !doc.is_object() || !usesMeshopt(doc)) return;
    std::string_view bin;
    const size_t binStart = 20 + size_t(jsonLength) + (4 - jsonLength % 4) % 4;
    if (binStart + 8 <= bytes.size() && readU32(bytes, binStart + 4) == kBinChunk) {
        const std::uint32_t binLength = readU32(bytes, binStart);
        if (binLength <= bytes.size() - binStart - 8) bin = std::string_view(bytes).substr(binStart + 8, binLength);
    }

    try {
        // The new binary chunk: the old one (uncompressed views keep their offsets), then each
        // decoded view, 4-byte aligned.
        std::string newBin(bin);
        if (!doc.contains("bufferViews") || !doc["bufferViews"].is_array()) throw Error("no bufferViews");
        for (size_t v = 0; v < doc["bufferViews"].size(); ++v) {
            json& view = doc["bufferViews"][v];
            if (!view.is_object() || !view.contains("extensions") || !view["extensions"].contains(kMeshopt)) continue;
            const std::string decoded =
                decodeView(view["extensions"][kMeshopt], bin, kMaxDecodedBytes - (newBin.size() - bin.size()),
                           "bufferViews[" + std::to_string(v) + "]");
            newBin.append((4 - newBin.size() % 4) % 4, '\0');
            view["buffer"] = std::uint64_t{0};
            view["byteOffset"] = newBin.size();
            view["byteLength"] = decoded.size();
            view["extensions"].erase(kMeshopt);
            newBin += decoded;
        }
        newBin.append((4 - newBin.size() % 4) % 4, '\0');
        // Fallback buffers hold nothing; the views that pointed into them now point into chunk 0.
        std::map<std::uint64_t, std::uint64_t> kept;  // old buffer index -> new
        json buffers = json::array();
        if (!doc.contains("buffers") || !doc["buffers"].is_array()) throw Error("no buffers");
        for (size_t b = 0; b < doc["buffers"].size(); ++b) {
            const json& buffer = doc["buffers"][b];
            const bool fallback = buffer.is_object() && buffer.contains("extensions") &&
                                  buffer["extensions"].contains(kMeshopt) &&
                                  buffer["extensions"][kMeshopt].value("fallback", false);
            if (fallback) continue;
            kept[b] = buffers.size();
            buffers.push_back(buffer);
        }
        if (buffers.empty() || kept.count(0) == 0 || buffers[0].contains("uri"))
            throw Error("the binary chunk is not buffer 0");
        buffers[0]["byteLength"] = newBin.size();
        doc["buffers"] = buffers;
        for (size_t v = 0; v < doc["bufferViews"].size(); ++v) {
            json& view = doc["bufferViews"][v];
            const std::uint64_t buffer = unsignedField(view, "buffer", "bufferViews[" + std::to_string(v) + "]");
            if (!kept.count(buffer))
                throw Error("bufferViews[" + std::to_string(v) + "] reads a fallback buffer uncompressed");
            view["buffer"] = kept[buffer];
        }
        for (const char* list : {"extensionsUsed", "extensionsRequired"}) {
            if (!doc.contains(list) || !doc[list].is_array()) continue;
            json names = json::array();
            for (const auto& name : doc[list])
                if (name != kMeshopt) names.push_back(name);
            doc[list] = names;
        }

        std::string text = doc.dump();
        text.append((4 - text.size() % 4) % 4, ' ');
        const std::uint64_t total = 12 + 8 + std::uint64_t(text.size()) + 8 + newBin.size();
        if (total > UINT32_MAX) throw Error("decompressed, larger than 4 GiB");
        std::string out = bytes.substr(0, 8);
        appendU32(out, std::uint32_t(total));
        appendU32(out, std::uint32_t(text.size()));
        appendU32(out, kJsonChunk);
        out += text;
        appendU32(out, std::uint32_t(newBin.size()));
        appendU32(out, kBinChunk);
        out += newBin;
        bytes = std::move(out);
    } catch (const Error& e) {
        throw fileError(path, std::string(kMeshopt) + ": " + e.what());
    } catch (const json::exception& e) {
        throw fileError(path, std::string(kMeshopt) + ": " + e.what());
    }
}

}  // namespace subdfit::mesh::gltf
