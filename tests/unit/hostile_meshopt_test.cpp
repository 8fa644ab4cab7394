// EXT_meshopt_compression views whose declared sizes are made to overflow or to decode into far
// more than the file holds: refused in one line naming the file, before anything is allocated.
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "bounded_run.h"
#include "error_message.h"
#include "glb_bytes.h"
#include "mesh/mesh_loader.h"
#include "test_paths.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::glb;

// One triangle whose positions view is meshopt-compressed with the given declared layout.
json compressedTriangle(std::uint64_t count, std::uint64_t stride, const std::string& mode = "ATTRIBUTES") {
    const json ext = {{"buffer", 0},          {"byteOffset", 0}, {"byteLength", 64},
                      {"byteStride", stride}, {"mode", mode},    {"count", count}};
    return {{"asset", {{"version", "2.0"}}},
            {"extensionsUsed", {"EXT_meshopt_compression"}},
            {"extensionsRequired", {"EXT_meshopt_compression"}},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
            {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
            {"bufferViews", {{{"buffer", 1}, {"byteLength", 36}, {"extensions", {{"EXT_meshopt_compression", ext}}}}}},
            {"buffers",
             {{{"byteLength", 64}},
              {{"byteLength", 36}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}}};
}

void expectRefusedNaming(const std::string& message, const std::string& file, const std::string& problem) {
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << "expected '" << problem << "' in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

// count × stride wraps to 4 in 64 bits: a 4-byte buffer that the decoder writes a block of
// vertices into before it runs out of data (version-0 header 0xA0, then zeros). In a child
// process: before the fix this smashed the heap or the stack.
TEST(HostileMeshopt, ACountWhoseProductWrapsIsRefusedBeforeDecoding) {
    const std::string data = "\xA0" + std::string(63, '\0');
    const std::uint64_t wraps = (std::uint64_t(1) << 62) + 1;
    for (const auto& [name, doc] : std::vector<std::pair<std::string, json>>{
             {"wraps.glb", compressedTriangle(wraps, 4)},
             {"wraps16.glb", compressedTriangle(wraps, 16)},
             {"wraps_indices.glb", compressedTriangle((std::uint64_t(1) << 63) + 3, 2, "TRIANGLES")}}) {
        const fs::path path = test::scratchDir("hostile_meshopt") / name;
        std::ofstream(path, std::ios::binary) << glb(doc, data);
        const auto outcome = test::runBounded(std::size_t(256) << 20, 10, [&] { loadReference(path); });
        ASSERT_TRUE(outcome.finished) << name << ": " << outcome.problem;
        expectRefusedNaming(outcome.error, name, "impossible size");
    }
}

// Views declaring 2 GiB each from 64 compressed bytes: refused before their buffers exist.
TEST(HostileMeshopt, ViewsTogetherMayNotDecodeBeyondTheLimit) {
    json doc = compressedTriangle(3, 12);
    const json big = {{"buffer", 0},       {"byteOffset", 0},      {"byteLength", 64},
                      {"byteStride", 256}, {"mode", "ATTRIBUTES"}, {"count", std::uint64_t(1) << 23}};  // 2 GiB each
    json views = json::array();
    for (int k = 0; k < 4; ++k)
        views.push_back({{"buffer", 1}, {"byteLength", 36}, {"extensions", {{"EXT_meshopt_compression", big}}}});
    views.push_back(doc["bufferViews"][0]);
    doc["bufferViews"] = views;
    doc["accessors"][0]["bufferView"] = 4;
    const fs::path path = test::scratchDir("hostile_meshopt") / "many_views.glb";
    std::ofstream(path, std::ios::binary) << glb(doc, std::string(64, '\0'));
    const auto outcome = test::runBounded(std::size_t(256) << 20, 10, [&] { loadReference(path); });
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    expectRefusedNaming(outcome.error, "many_views.glb", "impossible size");
}

}  // namespace
}  // namespace subdfit::mesh
