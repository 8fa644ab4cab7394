// Inputs that would cost unbounded time or memory, or never end: refused with a message that
// names the file and the limit, before the work is done.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <fstream>

#include "io/input_file.h"
#include "mesh/input_limits.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "subdiv/topology.h"
#include "error_message.h"
#include "test_paths.h"
#include "util/error.h"
#include "util/warnings.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;

// A disk: one n-gon, or n triangles around a centre vertex of valence n.
PolygonMesh disk(int n, bool fan) {
    PolygonMesh m;
    m.sourcePath = "disk.obj";
    if (fan) m.positions.push_back({0, 0, 0.3f});
    for (int i = 0; i < n; ++i) {
        const float a = 6.2831853f * float(i) / float(n);
        m.positions.push_back({std::cos(a), std::sin(a), 0.0f});
    }
    if (fan) {
        for (int i = 0; i < n; ++i) {
            m.faceSizes.push_back(3);
            m.faceIndices.insert(m.faceIndices.end(), {0, 1 + i, 1 + (i + 1) % n});
        }
    } else {
        m.faceSizes.push_back(n);
        for (int i = 0; i < n; ++i) m.faceIndices.push_back(i);
    }
    return m;
}

TEST(InputLimits, NonRegularFilesAreNeverOpenedForReading) {
    const auto dir = test::scratchDir("input_limits");
    ASSERT_EQ(mkfifo((dir / "pipe.obj").c_str(), 0600), 0);
    EXPECT_NE(test::errorMessage([&] { loadMesh(dir / "pipe.obj"); }).find("pipe.obj: is not a regular file"),
              std::string::npos);
    fs::create_symlink("/dev/zero", dir / "zero.obj");
    EXPECT_NE(test::errorMessage([&] { loadMesh(dir / "zero.obj"); }).find("zero.obj: is not a regular file"),
              std::string::npos);
    fs::create_directory(dir / "folder.obj");
    EXPECT_NE(test::errorMessage([&] { loadMesh(dir / "folder.obj"); }).find("is a folder"), std::string::npos);
}

TEST(InputLimits, AFileBeyondTheSizeLimitIsNotRead) {
    const auto dir = test::scratchDir("input_limits_size");
    std::ofstream(dir / "big.obj") << std::string(100, '#');
    const std::string message = test::errorMessage([&] { io::readInputFile(dir / "big.obj", 64); });
    EXPECT_NE(message.find("big.obj: is 100 bytes, more than the 64-byte input limit"), std::string::npos) << message;
    EXPECT_EQ(io::readInputFile(dir / "big.obj", 100).size(), 100u);
}

TEST(InputLimits, ALargeNgonIsRefusedAsACageButTriangulatedAsAReference) {
    const PolygonMesh ngon = disk(3000, false);
    const std::string message = test::errorMessage([&] { subdiv::buildTopologyRefiner(ngon); });
    EXPECT_NE(message.find("disk.obj: face 0 has 3000 vertices; a cage face may have at most 128"), std::string::npos)
        << message;
    EXPECT_EQ(triangulated(ngon).faceCount(), 2998);
    EXPECT_NO_THROW(subdiv::buildTopologyRefiner(disk(kMaxCageFaceSize, false)));
}

TEST(InputLimits, AVertexOfTooHighValenceIsRefusedInACage) {
    const std::string message =
        test::errorMessage([&] { subdiv::buildTopologyRefiner(disk(kMaxCageValence + 1, true)); });
    EXPECT_NE(message.find("vertex 0 is shared by more than 128 faces"), std::string::npos) << message;
    EXPECT_NO_THROW(subdiv::buildTopologyRefiner(disk(66, true)));  // OpenSubdiv's own valence-66 pole
}

TEST(InputLimits, ACageOfHolesIsRefusedBeforeAnyWork) {
    PolygonMesh cage = disk(8, true);
    for (int f = 0; f < cage.faceCount(); ++f) cage.tags.holes.push_back(f);
    EXPECT_NE(test::errorMessage([&] { subdiv::buildTopologyRefiner(cage); }).find("every face is tagged as a hole"),
              std::string::npos);
    cage.tags.holes.pop_back();
    EXPECT_NO_THROW(subdiv::buildTopologyRefiner(cage));
}

TEST(InputLimits, ACreaseBetweenVerticesThatShareNoEdgeIsWarnedAbout) {
    const auto dir = test::scratchDir("input_limits_crease");
    // A quad 0-1-2-3: 0-2 is a diagonal, not an edge; 0-1 is an edge.
    std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"
                                       "t crease 2/1/0 0 2 4.0\nt crease 2/1/0 0 1 4.0\n";
    std::vector<std::string> warnings;
    const auto previous = setWarningSink([&](const std::string& w) { warnings.push_back(w); });
    loadMesh(dir / "quad.obj");
    setWarningSink(previous);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("quad.obj: 1 crease tag joins vertices that share no edge (first: 0-2)"),
              std::string::npos)
        << warnings[0];
}

}  // namespace
}  // namespace subdfit::mesh
