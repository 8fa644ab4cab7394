// EXT_meshopt_compression under libFuzzer, structured: the first bytes choose a view's mode,
// filter, byte stride and element count (any 64-bit count: the products must be checked), the
// rest is its compressed data, wrapped in a valid GLB whose accessor reads the view. Any input
// must give a mesh or subdfit::Error; never a crash, a sanitizer report or an allocation past
// the fuzz run's limit (-malloc_limit_mb).
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "glb_bytes.h"
#include "mesh/gltf_meshopt.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"
#include "util/warnings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const auto quiet = subdfit::setWarningSink([](const std::string&) {});
    (void)quiet;
    if (size < 12) return 0;
    static const char* modes[] = {"ATTRIBUTES", "TRIANGLES", "INDICES", "OTHER"};
    static const char* filters[] = {"NONE", "OCTAHEDRAL", "QUATERNION", "EXPONENTIAL"};
    const std::string mode = modes[data[0] % 4], filter = filters[(data[0] >> 2) % 4];
    const std::uint64_t stride = std::uint64_t(data[1]) + (data[2] & 1 ? 256 : 0);
    std::uint64_t count;
    std::memcpy(&count, data + 3, 8);
    if (!(data[11] & 0x80)) count %= 4096;  // mostly counts the data could hold, sometimes any
    const bool indices = mode != "ATTRIBUTES";
    const std::string compressed(reinterpret_cast<const char*>(data + 12), size - 12);
    const nlohmann::json ext = {{"buffer", 0},          {"byteOffset", 0}, {"byteLength", compressed.size()},
                                {"byteStride", stride}, {"mode", mode},    {"filter", filter},
                                {"count", count}};
    nlohmann::json primitive = {{"attributes", {{"POSITION", indices ? 1 : 0}}}};
    if (indices) primitive["indices"] = 0;
    nlohmann::json doc;
    doc["asset"] = {{"version", "2.0"}};
    doc["extensionsUsed"] = doc["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
    doc["scenes"] = nlohmann::json::array({{{"nodes", {0}}}});
    doc["nodes"] = nlohmann::json::array({{{"mesh", 0}}});
    doc["meshes"] = nlohmann::json::array({{{"primitives", nlohmann::json::array({primitive})}}});
    doc["accessors"] =
        nlohmann::json::array({{{"bufferView", 0},
                                {"componentType", indices ? (stride == 2 ? 5123 : 5125) : 5126},
                                {"count", count % 65536},
                                {"type", indices ? "SCALAR" : "VEC3"}},
                               {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}});
    doc["bufferViews"] =
        nlohmann::json::array({{{"buffer", 1}, {"byteLength", 0}, {"extensions", {{"EXT_meshopt_compression", ext}}}},
                               {{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}});
    doc["buffers"] = nlohmann::json::array(
        {{{"byteLength", std::max<size_t>(compressed.size(), 36)}},
         {{"byteLength", 0}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
    std::string bin = compressed;
    if (bin.size() < 36) bin.resize(36, '\0');
    std::string bytes = subdfit::test::glb(doc, bin);
    try {
        subdfit::mesh::gltf::expandMeshopt(bytes, "fuzz.glb");
    } catch (const subdfit::Error&) {
        return 0;
    }
    // Expanded: the loader must take it or refuse it in one subdfit::Error.
    static const std::string path = "/dev/shm/subdfit_fuzz_meshopt_" + std::to_string(getpid()) + ".glb";
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        const std::string original = subdfit::test::glb(doc, bin);
        std::fwrite(original.data(), 1, original.size(), f);
        std::fclose(f);
    }
    try {
        (void)subdfit::mesh::loadReference(path);
    } catch (const subdfit::Error&) {}
    return 0;
}
