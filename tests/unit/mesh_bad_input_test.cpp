// The bad-input corpus (tests/data/bad): every file is refused with one subdfit::Error line
// that names the file and the problem, and nothing crashes.
#include <gtest/gtest.h>

#include "mesh/mesh_loader.h"
#include "error_message.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;

struct BadFile {
    const char* name;
    const char* problem;  // a fragment the message must contain
};

const BadFile kCorpus[] = {
    {"truncated.obj", "line 7: bad vertex coordinate"},
    {"index_out_of_range.obj", "line 5: face index 9 is out of range"},
    {"zero_index.obj", "line 4: face index 0"},
    {"nan_coordinate.obj", "line 2: non-finite vertex coordinate"},
    {"missing_coordinate.obj", "line 2: vertex has 2 coordinates"},
    {"coordinate_overflow.obj", "line 2: bad vertex coordinate"},
    {"empty.obj", "no faces"},
    {"no_faces.obj", "no faces"},
    {"two_vertex_face.obj", "line 4: face with 2 vertices"},
    {"bad_face_entry.obj", "line 4: bad face entry '3x'"},
    {"crease_out_of_range.obj", "line 5: t crease: vertex 3 is out of range"},
    {"huge_tag_count.obj", "line 5: t crease declares 2000000000/1/0 values but the line has 3"},
    {"bad_boundary_rule.obj", "line 5: t interpolateboundary: value 7"},
    {"bad_magic.glb", "not a GLB file"},
    {"truncated_length.glb", "invalid GLB"},
    {"meshopt_damaged.glb", "EXT_meshopt_compression: bufferViews[0] does not decode"},
    {"json_syntax.gltf", "invalid glTF"},
    {"accessor_out_of_bounds.gltf", "accessor 0 (10 elements"},
    {"index_out_of_range.gltf", "index 7 is out of range"},
    {"nan_position.gltf", "non-finite position"},
    {"truncated.drc", "corrupt Draco mesh"},
    {"point_cloud.drc", "point cloud"},
    {"mesh.txt", "unsupported mesh format '.txt'"},
    {"does_not_exist.obj", "cannot open"},
};

std::string errorFor(const fs::path& path) {
    return test::errorMessage([&] { loadMesh(path); });
}

TEST(MeshBadInput, EveryFileIsRefusedWithOneLineNamingFileAndProblem) {
    const fs::path dir = fs::path(SUBDFIT_SOURCE_DIR) / "tests" / "data" / "bad";
    for (const BadFile& bad : kCorpus) {
        SCOPED_TRACE(bad.name);
        const fs::path path = dir / bad.name;
        const std::string message = errorFor(path);
        ASSERT_FALSE(message.empty()) << "no error";
        EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
        EXPECT_NE(message.find(bad.problem), std::string::npos) << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

TEST(MeshBadInput, CorpusHasNoUntestedFile) {
    const fs::path dir = fs::path(SUBDFIT_SOURCE_DIR) / "tests" / "data" / "bad";
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string name = entry.path().filename().string();
        bool listed = false;
        for (const BadFile& bad : kCorpus) listed = listed || name == bad.name;
        EXPECT_TRUE(listed) << name;
    }
}

TEST(MeshBadInput, FolderIsNotAMesh) {
    const fs::path folder = test::scratchDir("MeshBadInput.Folder") / "folder.obj";
    fs::create_directories(folder);
    const std::string message = errorFor(folder);
    EXPECT_NE(message.find("folder.obj: is a folder"), std::string::npos) << message;
}

}  // namespace
}  // namespace subdfit::mesh
