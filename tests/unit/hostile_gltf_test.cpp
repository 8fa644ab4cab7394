// glTF files made to read what they should not or to cost what they should not: URIs that leave
// the file's folder (plainly, percent-encoded, absolute, by a scheme, by a symlink, or by
// tinygltf's fallback to the current directory), a node DAG instanced 2^30 times, negative
// offsets, counts that would allocate gigabytes. Each is refused with one line naming the file.
#include <gtest/gtest.h>

#include <unistd.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "mesh/gltf_preflight.h"
#include "mesh/mesh_loader.h"
#include "bounded_run.h"
#include "error_message.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// One triangle: three float positions, 36 bytes.
std::string triangleBytes() {
    const float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    return std::string(reinterpret_cast<const char*>(p), sizeof p);
}

json triangleGltf(const std::string& bufferUri) {
    return {{"asset", {{"version", "2.0"}}},
            {"scenes", {{{"nodes", {0}}}}},
            {"nodes", {{{"mesh", 0}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
            {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}}}},
            {"bufferViews", {{{"buffer", 0}, {"byteLength", 36}}}},
            {"buffers", {{{"uri", bufferUri}, {"byteLength", 36}}}}};
}

void write(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

std::string refusal(const fs::path& path) {
    return test::errorMessage([&] { loadMesh(path); });
}

class HostileGltf : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::scratchDir("hostile_gltf");
        // A "secret" beside the asset folder, of the size the buffer asks for, so that only the
        // containment rule can refuse it.
        write(dir_ / "secret.bin", triangleBytes());
        write(dir_ / "asset" / "ok.bin", triangleBytes());
    }
    fs::path gltfWith(const std::string& uri) {
        const fs::path path = dir_ / "asset" / "scene.gltf";
        write(path, triangleGltf(uri).dump());
        return path;
    }
    fs::path dir_;
};

TEST_F(HostileGltf, AReferenceInsideTheFolderLoads) {
    EXPECT_EQ(loadMesh(gltfWith("ok.bin")).faceCount(), 1);
    write(dir_ / "asset" / "my file.bin", triangleBytes());
    EXPECT_EQ(loadMesh(gltfWith("my%20file.bin")).faceCount(), 1);    // percent-decoded
    EXPECT_EQ(loadMesh(gltfWith("./sub/../ok.bin")).faceCount(), 1);  // climbs, but stays inside
}

TEST_F(HostileGltf, UrisThatLeaveTheFolderAreRefused) {
    const std::pair<std::string, std::string> cases[] = {
        {"../secret.bin", "leaves the glTF file's folder"},
        {"..%2Fsecret.bin", "leaves the glTF file's folder"},
        {"sub/../../secret.bin", "leaves the glTF file's folder"},
        {"%2E%2E/secret.bin", "leaves the glTF file's folder"},
        {(dir_ / "secret.bin").string(), "is an absolute path"},
        {"file://" + (dir_ / "secret.bin").string(), "scheme"},
        {"%zz.bin", "bad percent-escape"},
    };
    for (const auto& [uri, problem] : cases) {
        SCOPED_TRACE(uri);
        const std::string message = refusal(gltfWith(uri));
        EXPECT_NE(message.find("scene.gltf: buffers[0].uri"), std::string::npos) << message;
        EXPECT_NE(message.find(problem), std::string::npos) << message;
    }
}

TEST_F(HostileGltf, ASymlinkPointingOutIsRefused) {
    fs::create_symlink(dir_ / "secret.bin", dir_ / "asset" / "link.bin");
    const std::string message = refusal(gltfWith("link.bin"));
    EXPECT_NE(message.find("resolves outside the glTF file's folder"), std::string::npos) << message;
}

TEST_F(HostileGltf, TheCurrentFolderIsNeverSearched) {
    // tinygltf tries ./uri when baseDir/uri is missing: a file that exists only in the current
    // folder must not be found.
    const fs::path previous = fs::current_path();
    fs::current_path(dir_);
    const std::string message = refusal(gltfWith("secret.bin"));
    fs::current_path(previous);
    EXPECT_NE(message.find("scene.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("not found"), std::string::npos) << message;
    EXPECT_EQ(message.find("size mismatch"), std::string::npos)
        << "the message tells the outside file's size: " << message;
}

TEST_F(HostileGltf, AFifoIsNotOpened) {
    ASSERT_EQ(mkfifo((dir_ / "asset" / "pipe.bin").c_str(), 0600), 0);
    const std::string message = refusal(gltfWith("pipe.bin"));  // would block forever if opened
    EXPECT_NE(message.find("not a regular file"), std::string::npos) << message;
}

TEST_F(HostileGltf, AMissingImageIsNoReasonToRefuseTheGeometry) {
    json doc = triangleGltf("ok.bin");
    doc["images"] = {{{"uri", "textures/missing.png"}}};
    write(dir_ / "asset" / "scene.gltf", doc.dump());
    EXPECT_EQ(loadMesh(dir_ / "asset" / "scene.gltf").faceCount(), 1);
}

TEST_F(HostileGltf, AnImageOutsideTheFolderIsRefusedToo) {
    json doc = triangleGltf("ok.bin");
    doc["images"] = {{{"uri", "../../etc/passwd"}}};
    write(dir_ / "asset" / "scene.gltf", doc.dump());
    const std::string message = refusal(dir_ / "asset" / "scene.gltf");
    EXPECT_NE(message.find("images[0].uri"), std::string::npos) << message;
}

TEST_F(HostileGltf, NegativeOffsetsAndLengthsAreRefused) {
    for (const auto& [array, key] : {std::pair{"bufferViews", "byteOffset"},
                                     {"bufferViews", "byteLength"},
                                     {"accessors", "byteOffset"},
                                     {"accessors", "count"},
                                     {"buffers", "byteLength"}}) {
        SCOPED_TRACE(std::string(array) + "." + key);
        json doc = triangleGltf("ok.bin");
        doc[array][0][key] = -8;
        write(dir_ / "asset" / "scene.gltf", doc.dump());
        const std::string message = refusal(dir_ / "asset" / "scene.gltf");
        EXPECT_NE(message.find(std::string(array) + "[0]." + key + " is -8"), std::string::npos) << message;
    }
}

TEST_F(HostileGltf, AnAccessorCountBeyondTheLimitAllocatesNothing) {
    json doc = triangleGltf("ok.bin");
    doc["accessors"][0].erase("bufferView");  // all zeros: tinygltf checks no size against a buffer
    doc["accessors"][0]["count"] = 4000000000u;
    write(dir_ / "asset" / "scene.gltf", doc.dump());
    const std::string message = refusal(dir_ / "asset" / "scene.gltf");
    EXPECT_NE(message.find("more than"), std::string::npos) << message;
}

// Within the element limit, still 50 M zeros (600 MB of positions) from a few bytes of JSON.
TEST_F(HostileGltf, AnAccessorWithoutDataMayNotBeLarge) {
    json doc = triangleGltf("ok.bin");
    doc["accessors"][0].erase("bufferView");
    doc["accessors"][0]["count"] = 50000000;
    write(dir_ / "asset" / "zeros.gltf", doc.dump());
    const auto outcome = test::runBounded(std::size_t(256) << 20, 20, [&] { loadMesh(dir_ / "asset" / "zeros.gltf"); });
    ASSERT_TRUE(outcome.finished) << outcome.problem;
    EXPECT_NE(outcome.error.find("zeros.gltf"), std::string::npos) << outcome.error;
    EXPECT_NE(outcome.error.find("no buffer view"), std::string::npos) << outcome.error;
}

// The file: each node lists the next twice as children, so 30 nodes instance the last
// one's triangle 2^30 times. Refused by counting, before any of it is built.
TEST_F(HostileGltf, ANodeDagInstancedExponentiallyIsRefused) {
    json doc = triangleGltf("ok.bin");
    json nodes = json::array();
    for (int k = 0; k < 30; ++k) nodes.push_back({{"children", {k + 1, k + 1}}});
    nodes.push_back({{"mesh", 0}});
    doc["nodes"] = nodes;
    write(dir_ / "asset" / "scene.gltf", doc.dump());
    const std::string message = refusal(dir_ / "asset" / "scene.gltf");
    EXPECT_NE(message.find("unfolds into"), std::string::npos) << message;

    // A modest DAG (2^4 instances) is fine: shared nodes are legal glTF in practice.
    nodes = json::array();
    for (int k = 0; k < 4; ++k) nodes.push_back({{"children", {k + 1, k + 1}}});
    nodes.push_back({{"mesh", 0}});
    doc["nodes"] = nodes;
    write(dir_ / "asset" / "scene.gltf", doc.dump());
    EXPECT_EQ(loadMesh(dir_ / "asset" / "scene.gltf").faceCount(), 16);
}

TEST(GltfUris, ProblemsAreNamed) {
    EXPECT_EQ(gltf::uriProblem("data:application/octet-stream;base64,AAAA"), "");
    EXPECT_EQ(gltf::uriProblem("textures/a%20b.png"), "");
    EXPECT_NE(gltf::uriProblem(".."), "");
    EXPECT_NE(gltf::uriProblem("a/../../b"), "");
    EXPECT_NE(gltf::uriProblem("\\\\server\\share"), "");
    EXPECT_NE(gltf::uriProblem("http://example.com/a.bin"), "");
    EXPECT_NE(gltf::uriProblem("a%00.bin"), "");
    EXPECT_NE(gltf::uriProblem(""), "");
}

}  // namespace
}  // namespace subdfit::mesh
