// The USD export read back by Pixar's own USD (the pinned usd-core wheel in the virtual
// environment .ci/setup makes; tests/usd/read_usd.py): the stage opens, its topology and every
// UsdValidation validator pass, the rules and tags are the cage's, the displacement resolves
// to an image inside the package whose texels are the shipped heights, and the limit surface
// of the USD's own points and topology, evaluated with our OpenSubdiv code, is ours, with the
// face-varying `st` placing every tile where subdfit samples it.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "codec/map_atlas.h"
#include "codec/subd_format.h"
#include "export/usd/usd_export.h"
#include "mesh/mesh_loader.h"
#include "simplify/bake/atlas_bake.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/initial_cage.h"
#include "subdiv/limit_evaluator.h"
#include "test_paths.h"
#include "util/warnings.h"

namespace subdfit::test {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string quotedPath(const fs::path& path) { return "'" + path.string() + "'"; }

std::string readText(const fs::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// tests/usd/read_usd.py on `stage`: its stage.json. Throws (failing the test loudly) when the
// virtual environment is missing or the script fails.
json readWithUsd(const fs::path& stage, const fs::path& out) {
    const fs::path python = SUBDFIT_USD_PYTHON;
    if (!fs::exists(python))
        throw std::runtime_error(python.string() +
                                 " is missing: run .ci/setup, which installs the pinned usd-core wheel");
    const fs::path log = out.string() + ".log";
    const std::string command = quotedPath(python) + " " +
                                quotedPath(fs::path(SUBDFIT_SOURCE_DIR) / "tests/usd/read_usd.py") + " " +
                                quotedPath(stage) + " " + quotedPath(out) + " > " + quotedPath(log) + " 2>&1";
    if (std::system(command.c_str()) != 0) throw std::runtime_error("read_usd.py failed:\n" + readText(log));
    std::cout << readText(log);
    std::ifstream in(out / "stage.json");
    return json::parse(in);
}

// An image as floats in [0, 1], top row first.
struct Image {
    int width = 0, height = 0, channels = 0, bits = 0;
    std::vector<float> texels;
    float at(int x, int y, int c) const {
        return texels[(size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c)];
    }
    // Bilinear at pixel coordinates (x, y), texel centres on integers: a GPU's filtering at full
    // resolution, clamped to the edge.
    float bilinear(float x, float y, int c) const {
        x = glm::clamp(x, 0.0f, float(width - 1)), y = glm::clamp(y, 0.0f, float(height - 1));
        const int i = std::min(int(x), width - 2), j = std::min(int(y), height - 2);
        const float fx = x - float(i), fy = y - float(j);
        return (1 - fx) * (1 - fy) * at(i, j, c) + fx * (1 - fy) * at(i + 1, j, c) + (1 - fx) * fy * at(i, j + 1, c) +
               fx * fy * at(i + 1, j + 1, c);
    }
};

Image readImage(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw std::runtime_error(path.string() + ": " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    Image image{spec.width, spec.height, spec.nchannels, int(spec.format.size() * 8), {}};
    image.texels.resize(size_t(spec.width) * size_t(spec.height) * size_t(spec.nchannels));
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.texels.data()))
        throw std::runtime_error(path.string() + ": " + in->geterror());
    return image;
}

// The cage as the stage holds it, as a PolygonMesh our OpenSubdiv code evaluates.
mesh::PolygonMesh cageOf(const json& usd) {
    mesh::PolygonMesh cage;
    for (const auto& p : usd["points"])
        cage.positions.emplace_back(p[0].get<float>(), p[1].get<float>(), p[2].get<float>());
    cage.faceSizes = usd["faceVertexCounts"].get<std::vector<int>>();
    cage.faceIndices = usd["faceVertexIndices"].get<std::vector<int>>();
    const std::string boundary = usd["interpolateBoundary"];
    cage.tags.boundary = boundary == "none"            ? mesh::BoundaryInterpolation::None
                         : boundary == "edgeAndCorner" ? mesh::BoundaryInterpolation::EdgeAndCorner
                                                       : mesh::BoundaryInterpolation::EdgeOnly;
    cage.tags.triangles = usd["triangleSubdivisionRule"] == "smooth" ? mesh::TriangleSubdivision::Smooth
                                                                     : mesh::TriangleSubdivision::Catmark;
    const auto creaseIndices = usd["creaseIndices"].get<std::vector<int>>();
    const auto creaseSharpnesses = usd["creaseSharpnesses"].get<std::vector<float>>();
    const auto lengths = usd["creaseLengths"].get<std::vector<int>>();
    size_t at = 0;
    for (size_t c = 0; c < lengths.size(); ++c) {
        const bool perEdge = creaseSharpnesses.size() != lengths.size();
        for (int k = 0; k + 1 < lengths[c]; ++k)
            cage.tags.creases.push_back({creaseIndices[at + size_t(k)], creaseIndices[at + size_t(k) + 1],
                                         creaseSharpnesses[perEdge ? at - c + size_t(k) : c]});
        at += size_t(lengths[c]);
    }
    const auto cornerIndices = usd["cornerIndices"].get<std::vector<int>>();
    const auto cornerSharpnesses = usd["cornerSharpnesses"].get<std::vector<float>>();
    for (size_t k = 0; k < cornerIndices.size(); ++k)
        cage.tags.corners.push_back({cornerIndices[k], cornerSharpnesses[k]});
    cage.tags.holes = usd["holeIndices"].get<std::vector<int>>();
    cage.sourcePath = "the USD stage's cage";
    return cage;
}

// The face-varying value of `primvar` at corner k of quad f (texture coordinates come on
// all-quad cages alone).
glm::vec2 cornerValue(const json& primvar, int f, int k) {
    const size_t corner = 4 * size_t(f) + size_t(k);
    const size_t index = primvar["indices"].empty() ? corner : primvar["indices"][corner].get<size_t>();
    return {primvar["values"][index][0].get<float>(), primvar["values"][index][1].get<float>()};
}

// Where USD `st` falls on the atlas's tiles: the ptex face and its (u, v) (codec/map_atlas.h's
// formula inverted, v flipped to glTF's convention).
struct TilePoint {
    int face;
    glm::vec2 uv, pixel;
};
TilePoint tilePointOf(const codec::AtlasLayout& atlas, glm::vec2 st) {
    const glm::vec2 pixel(st.x * float(atlas.width) - 0.5f, (1.0f - st.y) * float(atlas.height) - 0.5f);
    const glm::ivec2 tile = glm::clamp(glm::ivec2(glm::floor((pixel + 0.5f) / float(atlas.tileSize))), glm::ivec2(0),
                                       glm::ivec2(atlas.columns - 1, atlas.rows - 1));
    const int face = tile.y * atlas.columns + tile.x;
    if (size_t(face) >= atlas.tileOrigins.size()) return {-1, glm::vec2(0.0f), pixel};  // outside every tile
    return {face, (pixel - glm::vec2(atlas.tileOrigins[size_t(face)])) / float(atlas.resolution), pixel};
}

struct Expected {
    bool refined = false;  // written refined once
};

// Everything the header promises, for `shipped` exported into `dir`.
void checkExport(const codec::SubdAsset& shipped, const fs::path& dir, const Expected& expected) {
    const json usd = readWithUsd(dir / "asset.usdz", dir / "read");
    ASSERT_TRUE(usd["opened"].get<bool>());
    int errors = 0;
    for (const auto& finding : usd["validation"])
        errors += finding["type"].get<std::string>().find("Error") != std::string::npos;
    EXPECT_EQ(errors, 0) << usd["validation"].dump(1);
    EXPECT_GE(usd["validators"].size(), 20u);  // the pinned usd-core registers 30
    EXPECT_EQ(usd["stage"]["upAxis"], "Y");    // as the glTF beside it, whatever the source
    EXPECT_EQ(usd["stage"]["metersPerUnit"].get<double>(), 1.0);
    EXPECT_TRUE(usd["stage"]["hasAuthoredMetersPerUnit"].get<bool>());
    EXPECT_EQ(usd["stage"]["defaultPrim"], "/Asset");

    const json& cage = usd["cage"];
    EXPECT_TRUE(cage["topologyValid"].get<bool>()) << cage["topologyReason"];
    EXPECT_EQ(cage["subdivisionScheme"], "catmullClark");
    EXPECT_EQ(cage["interpolateBoundary"], exporter::usdBoundaryToken(shipped.cage.tags.boundary));
    EXPECT_EQ(cage["triangleSubdivisionRule"], exporter::usdTriangleToken(shipped.cage.tags.triangles));
    EXPECT_EQ(cage["faceVaryingLinearInterpolation"], "all");
    const mesh::PolygonMesh theirs = cageOf(cage);

    // Tags: the cage's own, or each refined as one Catmull-Clark step refines it (Uniform
    // creasing): an interior crease edge becomes two of sharpness s − 1, a corner keeps its
    // vertex at s − 1, a hole face's children are holes.
    const mesh::SubdivisionTags& tags = shipped.cage.tags;
    size_t creases = 0, corners = 0, holes = 0;
    for (const auto& c : tags.creases) creases += c.sharpness > 1.0f;
    for (const auto& c : tags.corners) corners += c.sharpness > 1.0f;
    for (int h : tags.holes) holes += size_t(shipped.cage.faceSizes[size_t(h)]);
    if (expected.refined) {
        EXPECT_EQ(theirs.tags.creases.size(), 2 * creases);
        EXPECT_EQ(theirs.tags.corners.size(), corners);
        EXPECT_EQ(theirs.tags.holes.size(), holes);
        EXPECT_EQ(theirs.faceCount(), int(shipped.cage.faceIndices.size()));
    } else {
        EXPECT_EQ(theirs.tags.creases, tags.creases);
        EXPECT_EQ(theirs.tags.corners, tags.corners);
        EXPECT_EQ(theirs.tags.holes, tags.holes);
        EXPECT_EQ(theirs.faceIndices, shipped.cage.faceIndices);
    }
    for (const auto& c : theirs.tags.creases) EXPECT_LE(c.sharpness, 10.0f);  // USD's SHARPNESS_INFINITE is 10

    // The same patches: a refined cage is evaluated one isolation level shallower.
    const subdiv::LimitEvaluator ours(shipped.cage, {.isolationLevel = 3});
    const subdiv::LimitEvaluator usdLimit(theirs, {.isolationLevel = expected.refined ? 2 : 3});
    float size = 0.0f;
    for (const auto& p : shipped.cage.positions) size = std::max(size, glm::length(p));
    const surface::SurfaceMaps& maps = shipped.maps;
    const bool heights = maps.hasDisplacement();
    json displacement;
    Image heightImage;
    std::optional<codec::AtlasLayout> atlas;
    float scale = 0.0f, bias = 0.0f;
    if (heights) {
        ASSERT_TRUE(usd["material"]["inputs"].contains("displacement"));
        displacement = usd["material"]["inputs"]["displacement"];
        EXPECT_EQ(usd["material"]["displacement"], "UsdPreviewSurface");
        EXPECT_EQ(displacement["shader"], "UsdUVTexture");
        EXPECT_EQ(displacement["sourceColorSpace"], "raw");
        EXPECT_EQ(displacement["output"], "r");
        EXPECT_EQ(displacement["primvar"], "st");
        // Resolved inside the package: USD's path of a packaged file, read through its resolver.
        EXPECT_NE(displacement["resolved"].get<std::string>().find("asset.usdz[displacement.png]"), std::string::npos)
            << displacement["resolved"];
        heightImage = readImage(displacement["extracted"].get<std::string>());
        EXPECT_EQ(heightImage.bits, 16);
        atlas = codec::atlasLayout(maps.layout);
        ASSERT_EQ(heightImage.width, atlas->width);
        ASSERT_EQ(heightImage.height, atlas->height);
        scale = displacement["scale"][0].get<float>(), bias = displacement["bias"][0].get<float>();
        // Every node's texel is its shipped height, within the image's 16-bit quantisation.
        const float tolerance = 0.5f * scale / 65535.0f + 1e-6f * size;
        float worst = 0.0f;
        for (int face = 0; face < maps.layout.ptexFaceCount; ++face)
            for (int j = 0; j <= maps.layout.resolution; ++j)
                for (int i = 0; i <= maps.layout.resolution; ++i) {
                    const glm::ivec2 pixel = atlas->tileOrigins[size_t(face)] + glm::ivec2(i, j);
                    const float height = heightImage.at(pixel.x, pixel.y, 0) * scale + bias;
                    worst = std::max(worst, std::abs(height - maps.displacement[size_t(maps.layout.node(face, i, j))]));
                }
        EXPECT_LE(worst, tolerance);
    }

    // Sampled across every face of the stage: its limit surface is ours, and where `st` says
    // the point lies on our tiles, the texture's bilinear height is our tile's.
    double farthest = 0.0, worstHeight = 0.0;
    int compared = 0;
    int ptexOfTheirs = 0;
    for (int f = 0; f < theirs.faceCount(); ++f) {
        const int n = theirs.faceSizes[size_t(f)];
        for (int sub = 0; sub < (n == 4 ? 1 : n); ++sub, ++ptexOfTheirs)
            for (const glm::vec2 ab : {glm::vec2(0.5f), glm::vec2(0.2f, 0.7f), glm::vec2(0.85f, 0.1f)}) {
                if (!usdLimit.hasSurface(ptexOfTheirs, ab.x, ab.y)) continue;
                int face = ptexOfTheirs;
                glm::vec2 uv = ab;
                if (heights) {
                    ASSERT_EQ(n, 4);
                    const json& st = cage["primvars"]["st"];
                    const glm::vec2 value =
                        glm::mix(glm::mix(cornerValue(st, f, 0), cornerValue(st, f, 1), ab.x),
                                 glm::mix(cornerValue(st, f, 3), cornerValue(st, f, 2), ab.x), ab.y);
                    const TilePoint at = tilePointOf(*atlas, value);
                    ASSERT_GE(at.face, 0)
                        << "st " << value.x << ", " << value.y << " of face " << f << " is on no tile";
                    face = at.face, uv = at.uv;
                    const double height = heightImage.bilinear(at.pixel.x, at.pixel.y, 0) * scale + bias;
                    const double ours = surface::sampleBilinear(maps.layout, maps.displacement, 1, 0, face, uv.x, uv.y);
                    worstHeight = std::max(worstHeight, std::abs(height - ours));
                }
                ASSERT_TRUE(ours.hasSurface(face, uv.x, uv.y)) << "face " << f;
                const auto a = usdLimit.evaluate(ptexOfTheirs, ab.x, ab.y, theirs.positions);
                const auto b = ours.evaluate(face, uv.x, uv.y, shipped.cage.positions);
                farthest = std::max(farthest, double(glm::length(a.position - b.position)));
                ++compared;
            }
    }
    EXPECT_GT(compared, theirs.faceCount());
    EXPECT_LT(farthest, 1e-5 * size);
    if (heights) {
        EXPECT_LE(worstHeight, 0.5 * scale / 65535.0 + 1e-6 * size);
    }
    std::cout << "limit surface: " << compared << " points, farthest " << farthest << " (size " << size
              << "); heights: worst " << worstHeight << " (16-bit step " << scale / 65535.0f << ")\n";
}

// Heights and (optionally) a normal map on `cage`'s tiles: a few waves over the limit surface.
surface::SurfaceMaps wavyMaps(const mesh::PolygonMesh& cage, int resolution, bool normal) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(cage, resolution);
    maps.displacement.assign(size_t(maps.layout.nodeCount), 0.0f);
    if (normal) maps.normal.assign(2 * size_t(maps.layout.nodeCount), 0.0f);
    const subdiv::LimitEvaluator limit(cage);
    float size = 0.0f;
    for (const auto& p : cage.positions) size = std::max(size, glm::length(p));
    for (int face = 0; face < maps.layout.ptexFaceCount; ++face)
        for (int j = 0; j <= resolution; ++j)
            for (int i = 0; i <= resolution; ++i) {
                const float u = float(i) / float(resolution), v = float(j) / float(resolution);
                if (!limit.hasSurface(face, u, v)) continue;
                const glm::vec3 p = limit.evaluate(face, u, v, cage.positions).position / size;
                const auto node = size_t(maps.layout.node(face, i, j));
                maps.displacement[node] =
                    0.03f * size * (std::sin(9.0f * p.x + 2.0f * p.z) * std::cos(7.0f * p.y) + 0.3f);
                if (normal)
                    maps.normal[2 * node] = 0.3f * std::sin(5.0f * p.y),
                                    maps.normal[2 * node + 1] = 0.2f * std::cos(6.0f * p.x);
            }
    return maps;
}

// What ships: encoded as asset.subd, decoded again.
codec::SubdAsset shipped(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps) {
    return codec::decodeSubd(codec::encodeSubd(codec::shippableAsset(cage, maps)), "test asset");
}

bool allQuads(const mesh::PolygonMesh& cage) {
    return std::all_of(cage.faceSizes.begin(), cage.faceSizes.end(), [](int n) { return n == 4; });
}

struct Shape {
    const char* file;
    bool normal;
    friend void PrintTo(const Shape& shape, std::ostream* out) { *out << shape.file; }
};

class UsdExport : public ::testing::TestWithParam<Shape> {};

// OpenSubdiv's shapes: semi-sharp creases on triangles (written refined), semi-sharp creases on
// quads (written as they are), infinitely sharp creases, holes with boundaries and a triangle,
// and corners on an open surface.
TEST_P(UsdExport, OpensValidAndReproducesTheCageAndItsHeights) {
    const mesh::PolygonMesh cage = mesh::loadMesh(assetPath(GetParam().file));
    const codec::SubdAsset asset = shipped(cage, wavyMaps(cage, 4, GetParam().normal));
    const fs::path dir = scratchDir(std::string("usd_") + fs::path(GetParam().file).stem().string());
    exporter::writeUsd(dir, asset, true);
    checkExport(asset, dir, {.refined = !allQuads(cage)});
    if (GetParam().normal) {
        const json usd = readWithUsd(dir / "asset.usdz", dir / "read_normal");
        const json& normal = usd["material"]["inputs"]["normal"];
        EXPECT_EQ(normal["sourceColorSpace"], "raw");
        EXPECT_EQ(normal["primvar"], "st");
        EXPECT_EQ(normal["scale"], json({2, 2, 2, 1}));
        EXPECT_EQ(normal["bias"], json({-1, -1, -1, 0}));
    }
    // The text beside the package: the same stage, its images read from inside the package.
    const json beside = readWithUsd(dir / "asset.usda", dir / "read_text");
    EXPECT_TRUE(beside["validation"].empty()) << beside["validation"].dump(1);
    EXPECT_NE(beside["material"]["inputs"]["displacement"]["resolved"].get<std::string>().find(
                  "asset.usdz[displacement.png]"),
              std::string::npos);
    EXPECT_EQ(beside["cage"]["points"], readWithUsd(dir / "asset.usdz", dir / "read_again")["cage"]["points"]);
}

INSTANTIATE_TEST_SUITE_P(Shapes, UsdExport,
                         ::testing::Values(Shape{"osd-shapes/catmark_pyramid_creases2.obj", false},
                                           Shape{"osd-shapes/catmark_cube_creases1.obj", true},
                                           Shape{"osd-shapes/catmark_inf_crease0.obj", false},
                                           Shape{"osd-shapes/catmark_hole_test3.obj", false},
                                           Shape{"osd-shapes/catmark_edgecorner.obj", false}),
                         [](const auto& info) { return fs::path(info.param.file).stem().string(); });

// A cage without maps is written as it is, triangles and all: no texture coordinates to place.
TEST(UsdExport, ABareTriangleCageIsWrittenAsItIs) {
    const mesh::PolygonMesh cage = mesh::loadMesh(assetPath("spot/spot_control_mesh.obj"));
    ASSERT_FALSE(allQuads(cage));
    const codec::SubdAsset asset = shipped(cage, {});
    const fs::path dir = scratchDir("usd_bare_spot");
    exporter::writeUsd(dir, asset);
    checkExport(asset, dir, {.refined = false});
    EXPECT_FALSE(fs::exists(dir / "asset.usda"));
}

// A textured glTF as simplify makes it: a triangle cage from the reference, heights and the
// appearance in the reference's own texture atlas baked onto it; plus a normal texture,
// occlusion and emission on that atlas. glTF says Y up in metres.
TEST(UsdExport, ATexturedAssetCarriesItsAppearance) {
    const mesh::PolygonMesh reference = mesh::loadReference(assetPath("gltf/Duck/Duck.glb"));
    ASSERT_EQ(simplify::atlasUnsuitability(reference), "");
    const mesh::PolygonMesh cage = simplify::initialCage(reference, {.faces = 150});
    surface::SurfaceMaps maps =
        simplify::bakeMaps(cage, reference, {.effects = {maps::MapKind::Displacement}, .resolution = 3});
    maps.setAppearance(simplify::bakeAtlasAppearance(cage, reference,
                                                     {maps::MapKind::BaseColor, maps::MapKind::MetallicRoughness}, 32));
    const size_t texels = size_t(maps.appearanceLayout.nodeCount);
    maps.occlusion.assign(texels, 0.0f);
    maps.emissive.assign(3 * texels, 0.0f);
    maps.normalTexture.assign(3 * texels, 0.5f);
    for (size_t k = 0; k < texels; ++k) {
        maps.occlusion[k] = float(k % 7) / 6.0f;
        maps.emissive[3 * k] = float(k % 5) / 4.0f;
        maps.normalTexture[3 * k + 2] = 1.0f;
    }
    const codec::SubdAsset asset = shipped(cage, maps);
    ASSERT_TRUE(asset.maps.appearanceAtlas.present());
    const fs::path dir = scratchDir("usd_duck_atlas");
    exporter::writeUsd(dir, asset);
    checkExport(asset, dir, {.refined = true});

    const json usd = readWithUsd(dir / "asset.usdz", dir / "read_appearance");
    const json& inputs = usd["material"]["inputs"];
    const std::map<std::string, std::pair<std::string, std::string>> expected{
        {"diffuseColor", {"sRGB", "rgb"}}, {"roughness", {"raw", "g"}},        {"metallic", {"raw", "b"}},
        {"occlusion", {"raw", "r"}},       {"emissiveColor", {"sRGB", "rgb"}}, {"normal", {"raw", "rgb"}}};
    for (const auto& [input, how] : expected) {
        ASSERT_TRUE(inputs.contains(input)) << input;
        EXPECT_EQ(inputs[input]["sourceColorSpace"], how.first) << input;
        EXPECT_EQ(inputs[input]["output"], how.second) << input;
        EXPECT_EQ(inputs[input]["primvar"], "st1") << input;
        EXPECT_NE(inputs[input]["resolved"].get<std::string>().find("asset.usdz["), std::string::npos) << input;
    }
    // The base colour's texels are the shipped ones, and st1 is the atlas coordinates subdfit
    // blends across each ptex face, at every corner of the stage's faces.
    const codec::AtlasLayout grid = codec::atlasLayout(asset.maps.appearanceLayout);
    const auto pixels = codec::appearancePixels(grid, asset.maps, codec::AppearanceImage::BaseColor);
    const Image baseColor = readImage(inputs["diffuseColor"]["extracted"].get<std::string>());
    ASSERT_EQ(baseColor.width * baseColor.height * 3, int(pixels.size()));
    for (size_t k = 0; k < pixels.size(); ++k) ASSERT_EQ(std::lround(baseColor.texels[k] * 255.0f), pixels[k]) << k;
    const mesh::PolygonMesh theirs = cageOf(usd["cage"]);
    const codec::AtlasLayout heights = codec::atlasLayout(asset.maps.layout);
    float worst = 0.0f;
    for (int f = 0; f < theirs.faceCount(); ++f)
        for (int k = 0; k < 4; ++k) {
            const TilePoint at = tilePointOf(heights, cornerValue(usd["cage"]["primvars"]["st"], f, k));
            ASSERT_GE(at.face, 0);
            const glm::vec2 uv = surface::atlasUvAt(asset.maps.appearanceAtlas, at.face, at.uv.x, at.uv.y);
            worst = std::max(
                worst, glm::length(cornerValue(usd["cage"]["primvars"]["st1"], f, k) - glm::vec2(uv.x, 1.0f - uv.y)));
        }
    EXPECT_LT(worst, 1e-5f);
}

// The textured box with its appearance on per-face tiles (its texture coordinates leave the
// texture, so it has no atlas of its own): a creased cage, a second atlas read through st1.
TEST(UsdExport, AnAppearanceOnTilesHasItsOwnCoordinates) {
    const mesh::PolygonMesh reference = mesh::loadReference(assetPath("gltf/BoxTextured/BoxTextured.glb"));
    const mesh::PolygonMesh cage = simplify::initialCage(reference, {.faces = 12});
    ASSERT_FALSE(cage.tags.creases.empty());
    surface::SurfaceMaps maps = wavyMaps(cage, 2, false);
    maps.setAppearance(
        simplify::bakeAppearance(cage, reference, {.effects = {maps::MapKind::BaseColor}, .resolution = 4}));
    const codec::SubdAsset asset = shipped(cage, maps);
    const fs::path dir = scratchDir("usd_box_tiles");
    exporter::writeUsd(dir, asset);
    checkExport(asset, dir, {.refined = true});
    const json usd = readWithUsd(dir / "asset.usdz", dir / "read_tiles");
    EXPECT_EQ(usd["material"]["inputs"]["diffuseColor"]["primvar"], "st1");
    EXPECT_EQ(usd["cage"]["primvars"]["st1"]["interpolation"], "faceVarying");
}

// USD has no crease method: a Chaikin cage with semi-sharp creases is written, with a warning
// naming the package, never silently.
TEST(UsdExport, WarnsThatChaikinCreasesRenderUniform) {
    mesh::PolygonMesh cage = mesh::loadMesh(assetPath("osd-shapes/catmark_chaikin2.obj"));
    ASSERT_EQ(cage.tags.creaseMethod, mesh::CreaseMethod::Chaikin);
    std::vector<std::string> warnings;
    const auto previous = setWarningSink([&](const std::string& w) { warnings.push_back(w); });
    const fs::path dir = scratchDir("usd_chaikin");
    exporter::writeUsd(dir, shipped(cage, {}));
    cage.tags.creaseMethod = mesh::CreaseMethod::Uniform;
    exporter::writeUsd(dir, shipped(cage, {}));
    setWarningSink(previous);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("asset.usdz: USD has no Chaikin crease method"), std::string::npos) << warnings[0];
}

}  // namespace
}  // namespace subdfit::test
