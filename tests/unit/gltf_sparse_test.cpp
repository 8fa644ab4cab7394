// Sparse accessors (glTF 2.0, 3.6.2.3): values that replace some elements of a base accessor, or
// of zeros where it has no buffer view; and the files whose substitutions do not add up.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>

#include <nlohmann/json.hpp>

#include "mesh/mesh_loader.h"
#include "error_message.h"
#include "test_paths.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The buffer: a triangle's three float positions (36 bytes), two unsigned short indices (4),
// two float positions (24).
std::string bufferBytes(std::uint16_t first, std::uint16_t second) {
    const float base[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const std::uint16_t indices[2] = {first, second};
    const float values[6] = {0, 0, 5, 0, 2, 0};
    std::string bytes(64, '\0');
    std::memcpy(bytes.data(), base, 36);
    std::memcpy(bytes.data() + 36, indices, 4);
    std::memcpy(bytes.data() + 40, values, 24);
    return bytes;
}

json sparseTriangle(bool withBase) {
    json accessor = {
        {"componentType", 5126},
        {"count", 3},
        {"type", "VEC3"},
        {"sparse",
         {{"count", 2}, {"indices", {{"bufferView", 1}, {"componentType", 5123}}}, {"values", {{"bufferView", 2}}}}}};
    if (withBase) accessor["bufferView"] = 0;
    return {{"asset", {{"version", "2.0"}}},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
            {"accessors", {accessor}},
            {"bufferViews",
             {{{"buffer", 0}, {"byteLength", 36}},
              {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 4}},
              {{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 24}}}},
            {"buffers", {{{"uri", "sparse.bin"}, {"byteLength", 64}}}}};
}

fs::path writeAsset(const std::string& name, const json& doc, std::uint16_t first = 0, std::uint16_t second = 2) {
    const fs::path dir = test::scratchDir("gltf_sparse_" + fs::path(name).stem().string());  // its own buffer
    std::ofstream(dir / "sparse.bin", std::ios::binary) << bufferBytes(first, second);
    std::ofstream(dir / name) << doc.dump();
    return dir / name;
}

TEST(GltfSparse, ValuesReplaceTheirElementsOfTheBase) {
    const PolygonMesh mesh = loadMesh(writeAsset("based.gltf", sparseTriangle(true)));
    ASSERT_EQ(mesh.vertexCount(), 3);
    EXPECT_EQ(mesh.positions[0], glm::vec3(0, 0, 5));  // replaced
    EXPECT_EQ(mesh.positions[1], glm::vec3(1, 0, 0));  // the base's
    EXPECT_EQ(mesh.positions[2], glm::vec3(0, 2, 0));  // replaced
}

TEST(GltfSparse, WithoutABaseTheOtherElementsAreZero) {
    const PolygonMesh mesh = loadMesh(writeAsset("zeros.gltf", sparseTriangle(false)));
    ASSERT_EQ(mesh.vertexCount(), 3);
    EXPECT_EQ(mesh.positions[0], glm::vec3(0, 0, 5));
    EXPECT_EQ(mesh.positions[1], glm::vec3(0, 0, 0));
    EXPECT_EQ(mesh.positions[2], glm::vec3(0, 2, 0));
}

TEST(GltfSparse, SubstitutionsThatDoNotAddUpAreRefusedNamingTheFile) {
    json tooMany = sparseTriangle(true);
    tooMany["accessors"][0]["sparse"]["count"] = 4;  // more values than elements
    json pastTheView = sparseTriangle(true);
    pastTheView["accessors"][0]["sparse"]["values"]["byteOffset"] = 8;
    json badIndexType = sparseTriangle(true);
    badIndexType["accessors"][0]["sparse"]["indices"]["componentType"] = 5126;
    const struct {
        fs::path file;
        const char* problem;
    } cases[] = {
        {writeAsset("past.gltf", sparseTriangle(true), 0, 3), "sparse index 3 is past its 3 elements"},
        {writeAsset("order.gltf", sparseTriangle(true), 2, 1), "sparse index 1 is not above the one before it"},
        {writeAsset("repeat.gltf", sparseTriangle(true), 1, 1), "sparse index 1 is not above the one before it"},
        {writeAsset("many.gltf", tooMany), "4 sparse values, where 1 to 3 may be"},
        {writeAsset("view.gltf", pastTheView),
         "sparse values (24 bytes at offset 8) run past the end of buffer view 2"},
        {writeAsset("type.gltf", badIndexType), "sparse indices must be unsigned byte, short or int"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.file.string());
        const std::string message = test::errorMessage([&] { loadMesh(c.file); });
        EXPECT_NE(message.find(c.file.filename().string()), std::string::npos) << message;
        EXPECT_NE(message.find(c.problem), std::string::npos) << message;
    }
}

}  // namespace
}  // namespace subdfit::mesh
