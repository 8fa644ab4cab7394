// Map atlases: the tile layout, the EXR / PNG / JSON files, and the promise that a GPU bilinear
// sample at the atlas UV reproduces surface::sampleBilinear.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "codec/map_atlas.h"
#include "export/map_images.h"
#include "surface/texel_layout.h"
#include "mesh/procedural.h"
#include "test_paths.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

namespace fs = std::filesystem;

// Distinct values per node, so a pixel holding the wrong node shows.
surface::SurfaceMaps distinctMaps(int resolution) {
    surface::SurfaceMaps maps;
    maps.layout = surface::buildTexelLayout(mesh::makeQuadSphere(4), resolution);
    for (int n = 0; n < maps.layout.nodeCount; ++n) {
        maps.displacement.push_back(0.001f * float(n) - 0.2f);
        maps.normal.push_back(0.6f * std::sin(0.37f * float(n)));
        maps.normal.push_back(0.4f * std::cos(0.91f * float(n)));
    }
    return maps;
}

struct Image {
    OIIO::ImageSpec spec;
    std::vector<float> pixels;  // as float, whatever the file's format
};

Image readImage(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) throw Error(path.string() + ": " + OIIO::geterror());
    Image image{in->spec(), {}};
    image.pixels.resize(size_t(image.spec.width) * image.spec.height * image.spec.nchannels);
    if (!in->read_image(0, 0, 0, image.spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
        throw Error(path.string() + ": " + in->geterror());
    return image;
}

// What a GPU does for GL_LINEAR without mipmaps (clamp to edge): texel centres at +0.5.
float gpuBilinear(const std::vector<float>& image, int width, int height, glm::vec2 uv) {
    const float x = uv.x * float(width) - 0.5f, y = uv.y * float(height) - 0.5f;
    const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
    const float fx = x - float(x0), fy = y - float(y0);
    auto texel = [&](int px, int py) {
        return image[size_t(std::clamp(py, 0, height - 1)) * width + size_t(std::clamp(px, 0, width - 1))];
    };
    return (1 - fx) * (1 - fy) * texel(x0, y0) + fx * (1 - fy) * texel(x0 + 1, y0) + (1 - fx) * fy * texel(x0, y0 + 1) +
           fx * fy * texel(x0 + 1, y0 + 1);
}

TEST(ExportAtlas, TilesFormASquareishGridWithoutOverlap) {
    const surface::SurfaceMaps maps = distinctMaps(4);
    const codec::AtlasLayout atlas = codec::atlasLayout(maps.layout);
    ASSERT_EQ(maps.layout.ptexFaceCount, 96);
    EXPECT_EQ(atlas.tileSize, 5);
    EXPECT_EQ(atlas.columns, 10);  // ceil(sqrt(96))
    EXPECT_EQ(atlas.rows, 10);
    EXPECT_EQ(atlas.width, 50);
    EXPECT_EQ(atlas.height, 50);
    ASSERT_EQ(atlas.tileOrigins.size(), 96u);
    std::set<std::pair<int, int>> seen;
    for (const glm::ivec2& o : atlas.tileOrigins) {
        EXPECT_TRUE(seen.insert({o.x, o.y}).second);
        EXPECT_EQ(o.x % atlas.tileSize, 0);
        EXPECT_EQ(o.y % atlas.tileSize, 0);
        EXPECT_LE(o.x + atlas.tileSize, atlas.width);
        EXPECT_LE(o.y + atlas.tileSize, atlas.height);
    }
    EXPECT_EQ(atlas.tileOrigins[1], glm::ivec2(5, 0));  // row-major from the top-left
    EXPECT_EQ(atlas.tileOrigins[10], glm::ivec2(0, 5));

    surface::TexelLayout nine = maps.layout;
    nine.ptexFaceCount = 9;
    EXPECT_EQ(codec::atlasLayout(nine).columns, 3);  // an exact square stays exact
    nine.ptexFaceCount = 10;
    EXPECT_EQ(codec::atlasLayout(nine).columns, 4);
    EXPECT_EQ(codec::atlasLayout(nine).rows, 3);
}

TEST(ExportAtlas, GpuBilinearAtTheAtlasUvReproducesTheNodeInterpolation) {
    const surface::SurfaceMaps maps = distinctMaps(4);
    const codec::AtlasLayout atlas = codec::atlasLayout(maps.layout);
    const std::vector<float> image = codec::displacementAtlas(atlas, maps);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int face = 0; face < maps.layout.ptexFaceCount; ++face)
        for (int k = 0; k < 20; ++k) {
            // Include the tile borders, where a wrong half-texel would reach the next tile.
            const float u = k < 4 ? float(k & 1) : unit(rng), v = k < 4 ? float(k >> 1) : unit(rng);
            const float expected = surface::sampleBilinear(maps.layout, maps.displacement, 1, 0, face, u, v);
            EXPECT_NEAR(gpuBilinear(image, atlas.width, atlas.height, codec::atlasUv(atlas, face, u, v)), expected,
                        1e-5f)
                << "face " << face << " (" << u << ", " << v << ")";
        }
}

TEST(ExportAtlas, FilesReadBackWithTheNodeValuesAtTheirPixels) {
    const surface::SurfaceMaps maps = distinctMaps(4);
    const codec::AtlasLayout atlas = codec::atlasLayout(maps.layout);
    const fs::path dir = test::scratchDir("export_atlas_files");
    const std::vector<io::WrittenFile> written = writeMapAtlases(dir, maps);

    ASSERT_EQ(written.size(), 3u);
    EXPECT_EQ(written[0].path, dir / "displacement.exr");
    EXPECT_EQ(written[1].path, dir / "normal.png");
    EXPECT_EQ(written[2].path, dir / "maps.json");
    for (const io::WrittenFile& file : written) EXPECT_EQ(file.bytes, fs::file_size(file.path)) << file.path;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);  // no temporaries

    const Image exr = readImage(dir / "displacement.exr");
    EXPECT_EQ(exr.spec.nchannels, 1);
    EXPECT_EQ(exr.spec.format, OIIO::TypeDesc::FLOAT);
    const Image png = readImage(dir / "normal.png");
    EXPECT_EQ(png.spec.nchannels, 3);
    EXPECT_EQ(png.spec.format, OIIO::TypeDesc::UINT16);
    for (const Image* image : {&exr, &png}) {
        EXPECT_EQ(image->spec.width, atlas.width);
        EXPECT_EQ(image->spec.height, atlas.height);
    }

    for (int face = 0; face < maps.layout.ptexFaceCount; ++face)
        for (int j = 0; j <= 4; ++j)
            for (int i = 0; i <= 4; ++i) {
                const int node = maps.layout.node(face, i, j);
                const size_t pixel =
                    size_t(atlas.tileOrigins[face].y + j) * atlas.width + atlas.tileOrigins[face].x + i;
                ASSERT_EQ(exr.pixels[pixel], maps.displacement[node]) << "face " << face << " node " << i << "," << j;
                const glm::vec3 n = glm::normalize(glm::vec3(maps.normal[2 * node], maps.normal[2 * node + 1], 1.0f));
                for (int c = 0; c < 3; ++c)
                    ASSERT_NEAR(png.pixels[3 * pixel + c] * 2.0f - 1.0f, n[c], 2.0f / 65535.0f)
                        << "face " << face << " node " << i << "," << j << " channel " << c;
            }

    std::ifstream in(dir / "maps.json");
    const nlohmann::json manifest = nlohmann::json::parse(in);
    EXPECT_EQ(manifest["resolution"], 4);
    EXPECT_EQ(manifest["tileSize"], 5);
    EXPECT_EQ(manifest["columns"], atlas.columns);
    EXPECT_EQ(manifest["rows"], atlas.rows);
    EXPECT_EQ(manifest["width"], atlas.width);
    EXPECT_EQ(manifest["height"], atlas.height);
    ASSERT_EQ(manifest["ptexFaces"], 96);
    const int tile = manifest["tileSize"], columns = manifest["columns"];
    for (int f = 0; f < 96; ++f)  // the formula maps.json states
        EXPECT_EQ(atlas.tileOrigins[size_t(f)], glm::ivec2(tile * (f % columns), tile * (f / columns))) << f;
    EXPECT_EQ(manifest["displacement"]["file"], "displacement.exr");
    EXPECT_EQ(manifest["displacement"]["shading"], "the displaced surface's own normal");  // a DCC tool must know
    EXPECT_EQ(manifest["normal"]["file"], "normal.png");
    EXPECT_TRUE(manifest["uv"].is_string());
}

TEST(ExportAtlas, AbsentMapsWriteOnlyTheManifest) {
    surface::SurfaceMaps maps = distinctMaps(2);
    maps.displacement.clear();
    maps.normal.clear();
    const fs::path dir = test::scratchDir("export_atlas_absent");
    const std::vector<io::WrittenFile> written = writeMapAtlases(dir, maps);
    ASSERT_EQ(written.size(), 1u);
    EXPECT_EQ(written[0].path.filename(), "maps.json");
    std::ifstream in(dir / "maps.json");
    const nlohmann::json manifest = nlohmann::json::parse(in);
    EXPECT_FALSE(manifest.contains("displacement"));
    EXPECT_FALSE(manifest.contains("normal"));
}

TEST(ExportAtlas, UnwritableFolderThrowsAndLeavesNothing) {
    const surface::SurfaceMaps maps = distinctMaps(2);
    const fs::path dir = test::scratchDir("export_atlas_unwritable");
    std::ofstream(dir / "file") << "not a folder";
    try {
        writeMapAtlases(dir / "file", maps);
        FAIL() << "expected subdfit::Error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find((dir / "file" / "displacement.exr").string()), std::string::npos)
            << e.what();
    }
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);
}

}  // namespace
}  // namespace subdfit::exporter
