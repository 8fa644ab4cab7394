// What `simplify` ships: a light reference (a few hundred triangles) ships the triangle route,
// the reference whole, scored as that baseline is, with no cage fitted; and where no cage fits
// the budget, the triangle route that does ships instead of an error.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "export/gltf/glb_writer.h"
#include "export/gltf/textured_glb.h"
#include "fit/result_folder.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "simplify/simplify_job.h"
#include "small_simplify.h"
#include "test_paths.h"

namespace subdfit::test {
namespace {

namespace fs = std::filesystem;

TEST(SimplifyRoute, ALightReferenceShipsTheTriangleRouteWhole) {
    const auto dir = scratchDir("simplify_route_light");
    const mesh::PolygonMesh light = mesh::makeLumpySphere(3, 0.15f, 4);
    mesh::writeObj(dir / "light.obj", light);
    const auto report = simplify::toJson(simplify::runSimplify(smallSimplify(dir / "light.obj", dir / "out", 20)));

    // No --budget: the reference compressed (under the smallest default budget) is the budget,
    // and the triangle route holds all of it.
    EXPECT_TRUE(report["simplify"]["budget_derived"].get<bool>());
    const auto& route = report["route"];
    const std::string shipped = route["shipped"].get<std::string>();
    ASSERT_TRUE(shipped == "decimation" || shipped == "gltfpack") << route.dump();
    EXPECT_NE(route["why"].get<std::string>().find("whole"), std::string::npos) << route.dump();
    EXPECT_EQ(route["path"], "asset.glb");
    const auto& baseline = report["baselines"][shipped];
    EXPECT_EQ(baseline["triangles"].get<int>(), mesh::triangulated(light).faceCount());
    EXPECT_LT(baseline["triangles"].get<int>(), 2000);  // a light reference
    // What ships is the baseline: its file, its bytes, its scores; no cage was fitted.
    EXPECT_EQ(fs::file_size(dir / "out" / "asset.glb"), report["bytes"].get<std::uintmax_t>());
    EXPECT_EQ(report["bytes"], baseline["bytes"]);
    EXPECT_LE(report["bytes"].get<std::uintmax_t>(), report["simplify"]["budget"].get<std::uintmax_t>());
    EXPECT_EQ(report["psnr_holdout"], baseline["psnr_holdout"]);
    EXPECT_EQ(report["margin_db"][shipped].get<double>(), 0.0);
    // A smooth reference ships its normals: without, viewers would draw it flat.
    if (shipped == "decimation") {
        EXPECT_TRUE(baseline["encoding"]["normals"].get<bool>()) << baseline.dump();
    }
    EXPECT_GT(report["psnr_holdout"].get<double>(), 45.0);  // the reference's own look
    EXPECT_FALSE(report.contains("steps"));
    EXPECT_FALSE(fs::exists(dir / "out" / "asset.subd"));
    EXPECT_TRUE(report["seconds_by_stage"].contains("triangle_route"));
    EXPECT_FALSE(report["seconds_by_stage"].contains("fit"));
    // A viewer opens what shipped.
    const fit::ResultFolder folder = fit::readResultFolder(dir / "out");
    ASSERT_FALSE(folder.entries.empty());
    EXPECT_EQ(folder.entries.front().levels.front(), dir / "out" / "asset.glb");
}

// A light glTF without normals is drawn flat, as viewers draw it (the spec's rule): its triangles
// shipped without normals hold its look whole; shipping smooth ones would change it.
TEST(SimplifyRoute, ALightGltfWithoutNormalsShipsWholeAndFlat) {
    const auto dir = scratchDir("simplify_route_flat");
    const mesh::PolygonMesh light = mesh::triangulated(mesh::makeLumpySphere(3, 0.15f, 4));
    exporter::writeMeshGlb(dir / "flat.glb", light.positions, {},
                           std::vector<std::uint32_t>(light.faceIndices.begin(), light.faceIndices.end()), false);
    const auto report = simplify::toJson(simplify::runSimplify(smallSimplify(dir / "flat.glb", dir / "out", 20)));

    const auto& route = report["route"];
    ASSERT_EQ(route["shipped"], "decimation") << route.dump();
    EXPECT_NE(route["why"].get<std::string>().find("whole"), std::string::npos) << route.dump();
    const auto& baseline = report["baselines"]["decimation"];
    EXPECT_EQ(baseline["triangles"].get<int>(), light.faceCount());
    EXPECT_FALSE(baseline["encoding"]["normals"].get<bool>()) << baseline.dump();
    EXPECT_GT(report["psnr_holdout"].get<double>(), 45.0);  // the reference's own, flat look
    EXPECT_TRUE(mesh::loadMesh(dir / "out" / "asset.glb").normals.empty());
}

// A reference whose author set its normals (here all tilted one way, unlike any computed ones)
// ships them: the triangle route carries the reference's own normals, not smooth ones of its own.
TEST(SimplifyRoute, AuthoredNormalsShipWithTheReference) {
    const auto dir = scratchDir("simplify_route_authored_normals");
    const mesh::PolygonMesh light = mesh::triangulated(mesh::makeLumpySphere(3, 0.15f, 4));
    {
        std::ofstream obj(dir / "authored.obj");
        for (const auto& p : light.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
        obj << "vn 0.6 0.8 0\n";
        for (int f = 0; f < light.faceCount(); ++f) {
            obj << 'f';
            for (int k = 0; k < 3; ++k) obj << ' ' << light.faceIndices[size_t(3 * f + k)] + 1 << "//1";
            obj << '\n';
        }
    }
    const auto report = simplify::toJson(simplify::runSimplify(smallSimplify(dir / "authored.obj", dir / "out", 20)));
    const std::string shipped = report["route"]["shipped"].get<std::string>();
    ASSERT_EQ(shipped, "decimation") << report["route"].dump();
    EXPECT_TRUE(report["baselines"][shipped]["encoding"]["normals"].get<bool>());
    EXPECT_GT(report["psnr_holdout"].get<double>(), 45.0);
}

// `triangles`' faces as OBJ `f` lines whose corners take their second index (after `separator`:
// "/" texture coordinates, "//" normals) from a first set of one per vertex on the west half and a
// second set after it on the east half: the vertices along x = 0 split.
void writeFacesSplitEastWest(std::ostream& obj, const mesh::PolygonMesh& triangles, const char* separator) {
    const int n = triangles.vertexCount();
    for (int f = 0; f < triangles.faceCount(); ++f) {
        const int* corner = &triangles.faceIndices[size_t(3 * f)];
        const bool east = triangles.positions[size_t(corner[0])].x + triangles.positions[size_t(corner[1])].x +
                              triangles.positions[size_t(corner[2])].x >
                          0.0f;
        obj << 'f';
        for (int k = 0; k < 3; ++k) obj << ' ' << corner[k] + 1 << separator << corner[k] + 1 + (east ? n : 0);
        obj << '\n';
    }
}

// An OBJ without normals whose texture coordinates split its vertices along a seam is still
// shaded smooth (each position has one normal): the reference compressed (the default budget)
// carries its normals, and the triangle route ships it whole with them, not drawn flat.
TEST(SimplifyRoute, ASmoothReferenceSplitAtTextureSeamsShipsItsNormals) {
    const auto dir = scratchDir("simplify_route_seams");
    const mesh::PolygonMesh light = mesh::triangulated(mesh::makeLumpySphere(3, 0.15f, 4));
    const int n = light.vertexCount();
    {
        std::ofstream obj(dir / "seams.obj");
        for (const auto& p : light.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
        for (int side = 0; side < 2; ++side)
            for (const auto& p : light.positions)
                obj << "vt " << 0.5f * (float(side) + 0.5f + 0.5f * p.y) << ' ' << 0.5f + 0.5f * p.z << '\n';
        writeFacesSplitEastWest(obj, light, "/");
    }
    ASSERT_GT(mesh::loadReference(dir / "seams.obj").vertexCount(), n);  // split along the seam
    const auto report = simplify::toJson(simplify::runSimplify(smallSimplify(dir / "seams.obj", dir / "out", 20)));
    const std::string shipped = report["route"]["shipped"].get<std::string>();
    ASSERT_TRUE(shipped == "decimation" || shipped == "gltfpack") << report["route"].dump();
    EXPECT_NE(report["route"]["why"].get<std::string>().find("whole"), std::string::npos) << report["route"].dump();
    const auto& decimation = report["baselines"]["decimation"];
    EXPECT_EQ(decimation["triangles"].get<int>(), light.faceCount()) << decimation.dump();
    EXPECT_TRUE(decimation["encoding"]["normals"].get<bool>()) << decimation.dump();
    EXPECT_GT(report["psnr_holdout"].get<double>(), 40.0);  // smooth, as the reference is drawn
}

// A light reference whose author split its normals along a seam (a hard edge: its east half's
// normals tilted, the west half's not) ships as it is, the split kept: welded, its normals
// averaged along the seam, it would shade otherwise.
TEST(SimplifyRoute, AuthoredHardEdgesShipAsTheyAre) {
    const auto dir = scratchDir("simplify_route_hard_edges");
    const mesh::PolygonMesh light = mesh::triangulated(mesh::makeLumpySphere(3, 0.15f, 4));
    const std::vector<glm::vec3> smooth = mesh::vertexNormals(light);
    const int n = light.vertexCount();
    {
        std::ofstream obj(dir / "hard.obj");
        for (const auto& p : light.positions) obj << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
        for (const auto& v : smooth) obj << "vn " << v.x << ' ' << v.y << ' ' << v.z << '\n';
        for (const auto& v : smooth) {
            const glm::vec3 tilted = glm::normalize(v + glm::vec3(0.0f, 0.6f, 0.0f));
            obj << "vn " << tilted.x << ' ' << tilted.y << ' ' << tilted.z << '\n';
        }
        writeFacesSplitEastWest(obj, light, "//");
    }
    const auto report = simplify::toJson(simplify::runSimplify(smallSimplify(dir / "hard.obj", dir / "out", 20)));
    const auto& route = report["route"];
    ASSERT_EQ(route["shipped"], "decimation") << route.dump();
    EXPECT_NE(route["why"].get<std::string>().find("whole"), std::string::npos) << route.dump();
    const auto& decimation = report["baselines"]["decimation"];
    EXPECT_TRUE(decimation["encoding"]["normals"].get<bool>()) << decimation.dump();
    EXPECT_GT(mesh::loadMesh(dir / "out" / "asset.glb").vertexCount(), n);  // split along the seam
    EXPECT_GT(report["psnr_holdout"].get<double>(), 45.0);
}

// Two materials, so the appearance rides on tiles per face, which no cage of the ladder can
// afford at this budget; a decimated mesh of two plain colours can.
TEST(SimplifyRoute, WhereNoCageFitsTheTriangleRouteShips) {
    const auto dir = scratchDir("simplify_route_no_cage");
    mesh::PolygonMesh sphere = mesh::triangulated(mesh::makeQuadSphere(8));
    mesh::Material red = mesh::defaultMaterial(), blue = red;
    red.baseColorFactor = {0.8f, 0.1f, 0.1f, 1.0f};
    blue.baseColorFactor = {0.1f, 0.1f, 0.8f, 1.0f};
    sphere.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{red, blue}, {}});
    for (int f = 0; f < sphere.faceCount(); ++f)
        sphere.faceMaterials.push_back(sphere.positions[size_t(sphere.faceIndices[size_t(3 * f)])].y > 0.0f ? 1 : 0);
    exporter::writeTexturedGlb(dir / "two.glb", sphere, mesh::vertexNormals(sphere), {}, false);
    simplify::SimplifyOptions o = smallSimplify(dir / "two.glb", dir / "out", 10);
    o.budget = 2500;  // the smallest cage with tiles needs 3.6 KB; a decimation fits
    const auto report = simplify::toJson(simplify::runSimplify(o));
    const auto& route = report["route"];
    const std::string shipped = route["shipped"].get<std::string>();
    ASSERT_TRUE(shipped == "decimation" || shipped == "gltfpack") << route.dump();
    EXPECT_NE(route["why"].get<std::string>().find("no cage fits"), std::string::npos) << route.dump();
    EXPECT_LE(report["bytes"].get<std::uintmax_t>(), *o.budget);
    EXPECT_EQ(fs::file_size(dir / "out" / "asset.glb"), report["bytes"].get<std::uintmax_t>());
    EXPECT_FALSE(fs::exists(dir / "out" / "asset.subd"));
}

}  // namespace
}  // namespace subdfit::test
