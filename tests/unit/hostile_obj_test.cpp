// OBJ and MTL files made to read what they should not or to cost what they should not: material
// libraries and maps that reach out of the OBJ's folder through symlinks, FIFOs and folders in
// their place, control bytes in keywords, and tens of thousands of material names.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "error_message.h"
#include "io/image_io.h"
#include "mesh/mesh_loader.h"
#include "test_paths.h"
#include "util/warnings.h"

namespace subdfit::mesh {
namespace {

namespace fs = std::filesystem;
using test::errorMessage;

void writeText(const fs::path& path, const std::string& text) {
    fs::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

constexpr const char* kSecret = "SECRET-FIRST-LINE root:x:0:0";
constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl x\nf 1/1 2/2 3/3\n";

class HostileObj : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = test::scratchDir("hostile_obj");
        // Outside the asset's folder: a text file whose first line must never be shown, and an
        // image that must never be read.
        writeText(dir_ / "outside" / "secret.txt", std::string(kSecret) + "\nmore\n");
        io::writeImage(dir_ / "outside" / "secret.png", {{1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}, {1, 0, 0, 1}}, 2, 2);
        fs::create_directories(dir_ / "asset");
    }
    fs::path obj(const std::string& text) {
        const fs::path path = dir_ / "asset" / "m.obj";
        writeText(path, text);
        return path;
    }
    // Loads as a reference; the refusal (or "") and every warning together.
    std::string loaded(const fs::path& path) {
        std::string said;
        const auto previous = setWarningSink([&](const std::string& w) { said += w + "\n"; });
        said += errorMessage([&] { loadReference(path); });
        setWarningSink(previous);
        return said;
    }
    fs::path dir_;
};

TEST_F(HostileObj, AnMtlThatIsASymlinkOutOfTheFolderIsRefusedWithoutShowingIt) {
    fs::create_symlink(dir_ / "outside" / "secret.txt", dir_ / "asset" / "m.mtl");
    const std::string said = loaded(obj(std::string("mtllib m.mtl\n") + kTriangle));
    EXPECT_EQ(said.find("SECRET"), std::string::npos) << said;
    EXPECT_NE(said.find("m.mtl"), std::string::npos) << said;
    EXPECT_NE(said.find("outside the OBJ file's folder"), std::string::npos) << said;
}

TEST_F(HostileObj, AnMtlBehindASymlinkedFolderIsRefused) {
    fs::create_directory_symlink(dir_ / "outside", dir_ / "asset" / "d");
    const std::string said = loaded(obj(std::string("mtllib d/secret.txt\n") + kTriangle));
    EXPECT_EQ(said.find("SECRET"), std::string::npos) << said;
    EXPECT_NE(said.find("outside the OBJ file's folder"), std::string::npos) << said;
}

TEST_F(HostileObj, AMapThatIsASymlinkOutOfTheFolderIsNeverRead) {
    writeText(dir_ / "asset" / "m.mtl", "newmtl x\nmap_Kd t.png\n");
    fs::create_symlink("../outside/secret.png", dir_ / "asset" / "t.png");
    const std::string said = loaded(obj(std::string("mtllib m.mtl\n") + kTriangle));
    EXPECT_NE(said.find("t.png"), std::string::npos) << said;
    EXPECT_NE(said.find("outside the OBJ file's folder"), std::string::npos) << said;
}

TEST_F(HostileObj, SymlinksThatStayInsideTheFolderAreFollowed) {
    fs::create_directories(dir_ / "asset" / "maps");
    io::writeImage(dir_ / "asset" / "maps" / "real.png", {{0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}, {0, 0, 1, 1}}, 2,
                   2);
    fs::create_symlink("maps/real.png", dir_ / "asset" / "t.png");
    writeText(dir_ / "asset" / "lib" / "real.mtl", "newmtl x\nmap_Kd t.png\n");
    fs::create_symlink("lib/real.mtl", dir_ / "asset" / "m.mtl");
    const PolygonMesh mesh = loadReference(obj(std::string("mtllib m.mtl\n") + kTriangle));
    ASSERT_TRUE(mesh.materials);
    ASSERT_EQ(mesh.materials->images.size(), 1u);
    EXPECT_EQ(mesh.materials->images[0].width, 2);
    EXPECT_EQ(mesh.materials->images[0].rgba[2], 255);  // blue
}

TEST_F(HostileObj, FifosFoldersAndDevicesAreNotMaterialsOrMaps) {
    ASSERT_EQ(mkfifo((dir_ / "asset" / "fifo.mtl").c_str(), 0600), 0);
    EXPECT_NE(loaded(obj(std::string("mtllib fifo.mtl\n") + kTriangle)).find("not a regular file"), std::string::npos);
    fs::create_directories(dir_ / "asset" / "folder.mtl");
    EXPECT_NE(loaded(obj(std::string("mtllib folder.mtl\n") + kTriangle)).find("folder"), std::string::npos);
    fs::create_symlink("/dev/zero", dir_ / "asset" / "zero.png");
    writeText(dir_ / "asset" / "m.mtl", "newmtl x\nmap_Kd zero.png\n");
    const std::string said = loaded(obj(std::string("mtllib m.mtl\n") + kTriangle));
    EXPECT_NE(said.find("zero.png"), std::string::npos) << said;
    EXPECT_NE(said.find("outside the OBJ file's folder"), std::string::npos) << said;
}

// An escape sequence in a keyword would reach the terminal as it is.
TEST_F(HostileObj, ControlBytesFromTheFileAreNeverEchoedRaw) {
    writeText(dir_ / "asset" / "m.mtl", "newmtl x\n\x1b[31mred\x07 1 2\nmap_\x1b]0;title\x07 t.png\n");
    std::string said = loaded(obj(std::string("mtllib m.mtl\n") + kTriangle));
    EXPECT_NE(said.find("red"), std::string::npos) << said;
    EXPECT_EQ(said.find('\x1b'), std::string::npos) << said;
    EXPECT_EQ(said.find('\x07'), std::string::npos) << said;
    writeText(dir_ / "asset" / "m.mtl", "\x1b[2J 1\n");
    said = loaded(obj(std::string("mtllib m.mtl\n") + kTriangle));
    EXPECT_NE(said.find("before any newmtl"), std::string::npos) << said;
    EXPECT_EQ(said.find('\x1b'), std::string::npos) << said;
}

// Distinct `usemtl` names and MTL materials by the ten thousand: a lookup that scans every name
// takes about a minute here (n² string comparisons), a map a fraction of a second; the alarm
// ends the test binary long before the first.
TEST_F(HostileObj, TensOfThousandsOfMaterialNamesLoadInLinearTime) {
    constexpr int kNames = 200000, kMaterials = 40000;
    std::string mtl, text = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\n";
    for (int m = 0; m < kMaterials; ++m) mtl += "newmtl material" + std::to_string(m) + "\nKd 0.5 0.5 0.5\n";
    for (int n = 0; n < kNames; ++n) text += "usemtl material" + std::to_string(n) + "\nf 1 2 3\n";
    writeText(dir_ / "asset" / "m.mtl", mtl);
    const fs::path path = obj(text);
    alarm(20);
    const PolygonMesh mesh = loadReference(path);
    alarm(0);
    ASSERT_TRUE(mesh.materials);
    ASSERT_EQ(mesh.faceMaterials.size(), size_t(kNames));
    for (int f : {0, 1, kMaterials - 1})
        EXPECT_EQ(mesh.materials->materials.at(size_t(mesh.faceMaterials[size_t(f)])).name,
                  "material" + std::to_string(f));
    // Names the library lacks share one plain material.
    EXPECT_EQ(mesh.faceMaterials[size_t(kMaterials)], mesh.faceMaterials[size_t(kNames - 1)]);
    EXPECT_EQ(mesh.materials->materials.size(), size_t(kMaterials) + 1);
}

}  // namespace
}  // namespace subdfit::mesh
