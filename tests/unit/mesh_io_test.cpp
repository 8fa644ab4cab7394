// OBJ reading and writing: the OpenSubdiv regression shapes (all must load, with the counts
// and tags their README lists), OBJ syntax variants, and the write/read round trip.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "mesh/mesh_loader.h"
#include "mesh/obj_reader.h"
#include "mesh/obj_writer.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

fs::path writeText(const fs::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// What the README's table says about one shape.
struct ShapeFacts {
    int vertices = 0, faces = 0;
    std::map<std::string, int> tagLines;  // tag name -> number of `t` lines
};

std::map<std::string, ShapeFacts> readmeTable(const fs::path& readme) {
    std::map<std::string, ShapeFacts> table;
    std::istringstream lines(readText(readme));
    const std::regex row(R"(^\| (catmark_\w+\.obj) \| (\d+) \| (\d+) \([^|]*\) \|[^|]*\|[^|]*\|[^|]*\| ([^|]*) \|)");
    for (std::string line; std::getline(lines, line);) {
        std::smatch m;
        if (!std::regex_search(line, m, row)) continue;
        ShapeFacts facts{std::stoi(m[2]), std::stoi(m[3]), {}};
        std::istringstream tags(m[4].str());
        for (std::string tag; tags >> tag;)
            if (const auto colon = tag.find(':'); colon != std::string::npos)
                facts.tagLines[tag.substr(0, colon)] = std::stoi(tag.substr(colon + 1));
        table[m[1]] = facts;
    }
    return table;
}

int countLines(const std::string& text, const std::string& prefix) {
    int n = 0;
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) n += line.rfind(prefix, 0) == 0;
    return n;
}

void expectSameCage(const PolygonMesh& a, const PolygonMesh& b) {
    EXPECT_EQ(a.positions, b.positions);
    EXPECT_EQ(a.faceSizes, b.faceSizes);
    EXPECT_EQ(a.faceIndices, b.faceIndices);
    EXPECT_TRUE(a.tags == b.tags);
}

TEST(MeshObj, EveryOsdShapeLoadsWithTheReadmeCounts) {
    SUBDFIT_REQUIRE_SHARED(dir, "osd-shapes");
    const auto table = readmeTable(dir / "README.md");
    ASSERT_EQ(table.size(), 58u) << "README table rows";
    int loaded = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".obj") continue;
        const std::string name = entry.path().filename().string();
        SCOPED_TRACE(name);
        const PolygonMesh mesh = loadMesh(entry.path());
        const std::string text = readText(entry.path());
        EXPECT_EQ(mesh.vertexCount(), countLines(text, "v "));
        EXPECT_EQ(mesh.faceCount(), countLines(text, "f "));

        ASSERT_TRUE(table.count(name));
        const ShapeFacts& facts = table.at(name);
        EXPECT_EQ(mesh.vertexCount(), facts.vertices);
        EXPECT_EQ(mesh.faceCount(), facts.faces);
        auto lines = [&](const char* tag) { return facts.tagLines.count(tag) ? facts.tagLines.at(tag) : 0; };
        // Every crease and corner line in the set names one edge or vertex.
        EXPECT_EQ(int(mesh.tags.creases.size()), lines("crease"));
        EXPECT_EQ(int(mesh.tags.corners.size()), lines("corner"));
        EXPECT_EQ(int(mesh.tags.passthrough.size()), lines("vertexedit") + lines("edgeedit") + lines("faceedit"));
        EXPECT_EQ(mesh.tags.hasBoundary, lines("interpolateboundary") > 0);
        EXPECT_EQ(mesh.tags.hasFaceVaryingBoundary, lines("facevaryinginterpolateboundary") > 0);
        EXPECT_EQ(mesh.tags.hasCreaseMethod, lines("creasemethod") > 0);
        EXPECT_EQ(mesh.tags.hasTriangles, lines("smoothtriangles") > 0);
        ++loaded;
    }
    EXPECT_EQ(loaded, 58);
}

TEST(MeshObj, ParsesTagValues) {
    SUBDFIT_REQUIRE_SHARED(dir, "osd-shapes");
    const PolygonMesh creases = readObj(dir / "catmark_cube_creases1.obj");
    EXPECT_EQ(creases.vertexCount(), 8);
    EXPECT_EQ(creases.faceCount(), 6);
    ASSERT_EQ(creases.tags.creases.size(), 12u);
    EXPECT_TRUE(creases.tags.hasBoundary);

    const PolygonMesh hole = readObj(dir / "catmark_hole_test1.obj");
    EXPECT_EQ(hole.tags.holes.size(), 1u);
    EXPECT_EQ(readObj(dir / "catmark_hole_test3.obj").tags.holes.size(), 8u);

    EXPECT_EQ(readObj(dir / "catmark_edgenone.obj").tags.boundary, BoundaryInterpolation::None);
    EXPECT_EQ(readObj(dir / "catmark_edgecorner.obj").tags.boundary, BoundaryInterpolation::EdgeAndCorner);
    EXPECT_EQ(readObj(dir / "catmark_dart_edgeonly.obj").tags.boundary, BoundaryInterpolation::EdgeOnly);
    // Without the tag, OpenSubdiv's regression default.
    const PolygonMesh plain = readObj(dir / "catmark_cube.obj");
    EXPECT_FALSE(plain.tags.hasBoundary);
    EXPECT_EQ(plain.tags.boundary, BoundaryInterpolation::EdgeOnly);

    EXPECT_EQ(readObj(dir / "catmark_chaikin0.obj").tags.creaseMethod, CreaseMethod::Uniform);
    EXPECT_EQ(readObj(dir / "catmark_chaikin2.obj").tags.creaseMethod, CreaseMethod::Chaikin);
    const PolygonMesh tris = readObj(dir / "catmark_smoothtris0.obj");
    EXPECT_TRUE(tris.tags.hasTriangles);
    EXPECT_EQ(tris.tags.triangles, TriangleSubdivision::Catmark);
    EXPECT_EQ(readObj(dir / "catmark_cubes_infsharp.obj").tags.faceVaryingBoundary, 1);

    const PolygonMesh corner = readObj(dir / "catmark_cube_corner0.obj");
    ASSERT_EQ(corner.tags.corners.size(), 1u);
    EXPECT_FLOAT_EQ(corner.tags.corners[0].sharpness, 0.7f);

    const PolygonMesh edit = readObj(dir / "catmark_square_hedit4.obj");
    ASSERT_EQ(edit.tags.passthrough.size(), 2u);
    EXPECT_EQ(edit.tags.passthrough[1], "t faceedit 4/0/1 3 4 1 1 hole");

    const PolygonMesh bishop = readObj(dir / "catmark_bishop.obj");
    EXPECT_EQ(bishop.vertexCount(), 917);
    EXPECT_EQ(bishop.faceCount(), 968);
    EXPECT_EQ(bishop.tags.creases.size(), 224u);
}

TEST(MeshObj, ReadsFaceEntryFormsNegativeIndicesAndCrlf) {
    const auto dir = test::scratchDir("MeshObj.Forms");
    const auto path = writeText(dir / "forms.obj",
                                "# comment\r\n"
                                "mtllib x.mtl\r\n"
                                "o thing\r\n"
                                "v 0 0 0\r\n"
                                "v +1.5 0 0 1\r\n"            // w is ignored, '+' accepted
                                "v 0 1e-3 0 0.5 0.5 0.5\r\n"  // vertex colours ignored
                                "v 1 1 -0\r\n"
                                "vt 0 0\r\nvn 0 0 1\r\n"
                                "g group\r\ns 1\r\nusemtl m\r\n"
                                "f 1/1 2/1/1 3//1\r\n"
                                "f -4 -3 -1 -2\r\n"
                                "t crease 4/2/0 0 1 1 2 2.5 10\r\n"
                                "t corner 2/1/0 0 3 1.5\r\n");
    const PolygonMesh mesh = readObj(path);
    ASSERT_EQ(mesh.vertexCount(), 4);
    EXPECT_EQ(mesh.positions[1], glm::vec3(1.5f, 0, 0));
    EXPECT_EQ(mesh.positions[2], glm::vec3(0, 1e-3f, 0));
    EXPECT_EQ(mesh.faceSizes, (std::vector<int>{3, 4}));
    EXPECT_EQ(mesh.faceIndices, (std::vector<int>{0, 1, 2, 0, 1, 3, 2}));
    ASSERT_EQ(mesh.tags.creases.size(), 2u);
    EXPECT_EQ(mesh.tags.creases[1], (Crease{1, 2, 10.0f}));
    ASSERT_EQ(mesh.tags.corners.size(), 2u);
    EXPECT_EQ(mesh.tags.corners[1], (Corner{3, 1.5f}));
    EXPECT_EQ(mesh.sourcePath, path.string());
}

TEST(MeshObj, RoundTripsEveryOsdShape) {
    SUBDFIT_REQUIRE_SHARED(dir, "osd-shapes");
    const auto out = test::scratchDir("MeshObj.RoundTrip");
    for (const auto& entry : fs::directory_iterator(dir)) {
        if (entry.path().extension() != ".obj") continue;
        SCOPED_TRACE(entry.path().filename().string());
        const PolygonMesh original = readObj(entry.path());
        const auto copy = out / entry.path().filename();
        writeObj(copy, original);
        expectSameCage(readObj(copy), original);
    }
}

TEST(MeshObj, RoundTripKeepsEveryFloatBitAndExplicitRules) {
    PolygonMesh mesh;
    mesh.positions = {{0.1f, -1e-30f, 3.4e38f}, {1.0f / 3.0f, 1e-45f, -7.25f}, {123456.789f, 0, 2}};
    mesh.faceSizes = {3};
    mesh.faceIndices = {2, 0, 1};
    mesh.tags.creases = {{0, 1, 0.3f}};
    mesh.tags.corners = {{2, 1.0f / 7.0f}};
    mesh.tags.holes = {0};
    mesh.tags.boundary = BoundaryInterpolation::None;
    mesh.tags.hasBoundary = true;
    mesh.tags.faceVaryingBoundary = 4;
    mesh.tags.hasFaceVaryingBoundary = true;
    mesh.tags.creaseMethod = CreaseMethod::Chaikin;
    mesh.tags.hasCreaseMethod = true;
    mesh.tags.triangles = TriangleSubdivision::Smooth;
    mesh.tags.hasTriangles = true;
    mesh.tags.passthrough = {"t vertexedit 4/0/3 1 2 3 4 add P value"};

    const auto path = test::scratchDir("MeshObj.Bits") / "cage.obj";
    writeObj(path, mesh);
    expectSameCage(readObj(path), mesh);
}

TEST(MeshObj, WriteIsAtomicAndCleansUp) {
    const auto dir = test::scratchDir("MeshObj.Atomic");
    PolygonMesh mesh;
    mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh.faceSizes = {3};
    mesh.faceIndices = {0, 1, 2};

    const auto path = writeText(dir / "cage.obj", "old contents\n");
    writeObj(path, mesh);
    EXPECT_EQ(readObj(path).faceCount(), 1);
    // Nothing but the target is left in the folder.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

    // A folder that does not exist: an error naming the file, and nothing created.
    const auto missing = dir / "no-such-folder" / "cage.obj";
    try {
        writeObj(missing, mesh);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
    }
    // A non-finite position is refused before the old file is touched.
    mesh.positions[1].x = std::numeric_limits<float>::infinity();
    EXPECT_THROW(writeObj(path, mesh), Error);
    EXPECT_EQ(readObj(path).faceCount(), 1);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace subdfit::mesh
