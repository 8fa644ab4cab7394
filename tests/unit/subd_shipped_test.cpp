// What `subdfit decode` and the web decoder (apps/web) share: the reader that leaves the images
// encoded (readShippedSubd, with their sizes from the JPEG headers) and the surface both draw.
#include <gtest/gtest.h>

#include <zstd.h>

#include "error_message.h"
#include "subd_bytes.h"

#include "codec/byte_stream.h"
#include "codec/subd_format.h"
#include "export/surface_mesh.h"
#include "io/image_header.h"
#include "io/image_io.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "util/error.h"
#include "util/hash.h"

namespace subdfit::codec {
namespace {

// A base colour, roughness-metallic and emission on tiles of the cage, all grey 0.5.
SubdAsset greyAppearance(const mesh::PolygonMesh& cage, int resolution) {
    surface::SurfaceMaps maps;
    maps.appearanceLayout = surface::buildTexelLayout(cage, resolution);
    const size_t nodes = size_t(maps.appearanceLayout.nodeCount);
    maps.baseColor.assign(3 * nodes, 0.5f);
    maps.metallicRoughness.assign(2 * nodes, 0.5f);
    maps.occlusion.assign(nodes, 0.5f);
    maps.emissive.assign(3 * nodes, 0.5f);
    return shippableAsset(cage, maps);
}

TEST(ImageHeader, AJpegStatesItsSizeAndNothingElseDoes) {
    const io::DecodedImage image{37, 21, std::vector<std::uint8_t>(37 * 21 * 4, 200)};
    const auto jpeg = io::encodeImage(image, 37, 21, io::ImageFormat::Jpeg, 90);
    EXPECT_EQ(io::jpegHeader(jpeg), (io::ImageHeader{37, 21, 3}));
    const auto png = io::encodeImage(image, 37, 21, io::ImageFormat::Png);
    EXPECT_FALSE(io::jpegHeader(png));
    EXPECT_FALSE(io::jpegHeader(std::span<const unsigned char>(jpeg).first(20)));  // cut before its frame header
    EXPECT_FALSE(io::jpegHeader({}));
    // The reader of every format gives the same header, a PNG's through OpenImageIO.
    EXPECT_EQ(io::readImageHeader(jpeg.data(), jpeg.size(), "a.jpg"), (io::ImageHeader{37, 21, 3}));
    EXPECT_EQ(io::readImageHeader(png.data(), png.size(), "a.png").width, 37);
    EXPECT_EQ(io::readImageHeader(png.data(), png.size(), "a.png").height, 21);
    EXPECT_THROW(io::readImageHeader(jpeg.data(), 20, "cut.jpg"), Error);
}

TEST(SubdShipped, TheReaderKeepsTheImagesEncodedAndDecodeSubdDecodesThem) {
    const auto cage = mesh::makeQuadSphere(2);
    const auto bytes = encodeSubd(greyAppearance(cage, 4));
    const ShippedSubd shipped = readShippedSubd(bytes, "grey.subd");
    ASSERT_EQ(shipped.images.size(), 3u);
    EXPECT_EQ(shipped.images[0].which, AppearanceImage::BaseColor);
    EXPECT_EQ(shipped.images[1].which, AppearanceImage::MetallicRoughness);
    EXPECT_TRUE(shipped.images[1].occlusion);
    EXPECT_EQ(shipped.images[2].which, AppearanceImage::Emissive);
    const AtlasLayout atlas = atlasLayout(shipped.asset.maps.appearanceLayout);
    for (const ShippedImage& image : shipped.images) {
        EXPECT_EQ(image.width, atlas.width);
        EXPECT_EQ(image.height, atlas.height);
        EXPECT_EQ(io::jpegHeader(image.bytes), (io::ImageHeader{atlas.width, atlas.height, 3}));
    }
    EXPECT_FALSE(shipped.asset.maps.hasBaseColor());  // the values are the caller's to decode

    const SubdAsset decoded = decodeSubd(bytes, "grey.subd");
    ASSERT_TRUE(decoded.maps.hasBaseColor());
    EXPECT_NEAR(decoded.maps.baseColor[0], 0.5f, 2.0f / 255.0f);
    EXPECT_EQ(decoded.maps.occlusion.size(), size_t(decoded.maps.appearanceLayout.nodeCount));
    EXPECT_EQ(decoded.cage.positions, shipped.asset.cage.positions);
}

// The file with its BCOL section's JPEG replaced by `jpeg` (sections re-compressed, checksums
// recomputed).
std::vector<unsigned char> withBaseColorJpeg(const std::vector<unsigned char>& file,
                                             const std::vector<unsigned char>& jpeg) {
    ByteReader in(std::span<const unsigned char>(file).first(file.size() - 8), "file");
    ByteWriter out;
    out.putBytes(in.take(8));
    const auto count = in.get<std::uint32_t>();
    out.put<std::uint32_t>(count);
    out.put<std::uint32_t>(in.get<std::uint32_t>());  // decode triangles
    for (std::uint32_t k = 0; k < count; ++k) {
        const auto tag = in.take(4);
        const auto storedSize = in.get<std::uint32_t>(), rawSize = in.get<std::uint32_t>();
        const auto stored = in.take(storedSize);
        std::vector<unsigned char> raw(rawSize);
        raw.resize(ZSTD_decompress(raw.data(), raw.size(), stored.data(), stored.size()));
        if (std::string(tag.begin(), tag.end()) == "BCOL") {
            ByteReader section(raw, "BCOL");
            ByteWriter replaced;
            replaced.putVarint(section.getVarint());  // T
            replaced.putVarint(section.getVarint());  // node count
            replaced.put<std::uint8_t>(section.get<std::uint8_t>());
            section.take(section.getVarint());
            replaced.putVarint(jpeg.size());
            replaced.putBytes(jpeg);
            raw = replaced.bytes();
        }
        std::vector<unsigned char> compressed = test::checksummedFrame(raw);
        out.putBytes(tag);
        out.put<std::uint32_t>(std::uint32_t(compressed.size()));
        out.put<std::uint32_t>(std::uint32_t(raw.size()));
        out.putBytes(compressed);
    }
    out.put<std::uint64_t>(hash64({reinterpret_cast<const char*>(out.bytes().data()), out.bytes().size()}));
    return std::move(out.bytes());
}

// An image whose header states another size than its lattice's atlas is refused before any
// pixel is decoded (a few KB of JPEG may state 16384²).
TEST(SubdShipped, AnImageOfTheWrongSizeIsRefusedFromItsHeader) {
    const auto cage = mesh::makeQuadSphere(2);
    const auto good = encodeSubd(greyAppearance(cage, 4));
    const ShippedSubd shipped = readShippedSubd(good, "grey.subd");
    const ShippedImage& image = shipped.images[0];
    const io::DecodedImage wider{image.width + 1, image.height,
                                 std::vector<std::uint8_t>(size_t(image.width + 1) * size_t(image.height) * 4, 128)};
    const auto bad =
        withBaseColorJpeg(good, io::encodeImage(wider, wider.width, wider.height, io::ImageFormat::Jpeg, 90));
    const std::string expected = "bad.subd: BCOL section: the image is " + std::to_string(image.width + 1) + " x " +
                                 std::to_string(image.height) + ", the atlas " + std::to_string(image.width) + " x " +
                                 std::to_string(image.height);
    EXPECT_EQ(test::errorMessage([&] { readShippedSubd(bad, "bad.subd"); }), expected);
    EXPECT_EQ(test::errorMessage([&] { decodeSubd(bad, "bad.subd"); }), expected);
    const auto png = withBaseColorJpeg(good, io::encodeImage(wider, image.width, image.height, io::ImageFormat::Png));
    EXPECT_EQ(test::errorMessage([&] { readShippedSubd(png, "png.subd"); }),
              "png.subd: BCOL section: not a JPEG image");
    // The same JPEG put back decodes as before.
    EXPECT_EQ(readShippedSubd(withBaseColorJpeg(good, image.bytes), "same.subd").images[0].bytes, image.bytes);
}

TEST(SubdShipped, TheSurfaceDecodeWritesHasTheMaterialsTexturesAndFactors) {
    const auto cage = mesh::makeQuadSphere(2);
    const SubdAsset asset = decodeSubd(encodeSubd(greyAppearance(cage, 4)), "grey.subd");
    const exporter::SurfaceTextures textures = exporter::SurfaceTextures::of(asset.maps);
    EXPECT_TRUE(textures.baseColor && textures.metallicRoughness && textures.occlusion && textures.emissive);
    EXPECT_FALSE(textures.normalMap || textures.normalTexture);
    const exporter::SurfaceMaterial material = exporter::surfaceMaterial(textures);
    EXPECT_EQ(material.metallicFactor, 1.0);
    EXPECT_EQ(material.roughnessFactor, 1.0);
    EXPECT_EQ(material.emissiveFactor[0], 1.0);
    EXPECT_EQ(exporter::surfaceMaterial({}).roughnessFactor, 0.5);  // Blender's default surface without a base colour

    const exporter::GltfMesh mesh = surfaceGltfMesh(asset.cage, asset.maps, textures, 3);
    const auto tessellation = surface::tessellate(asset.cage, asset.maps, 3);
    EXPECT_EQ(mesh.positions, tessellation.positions);
    EXPECT_EQ(mesh.indices, tessellation.indices);
    const AtlasLayout atlas = atlasLayout(asset.maps.appearanceLayout);
    for (const glm::vec2& uv : mesh.uvs) {  // on the appearance atlas, inside it
        EXPECT_GT(uv.x, 0.0f);
        EXPECT_LT(uv.x, 1.0f);
        EXPECT_LT(uv.y * float(atlas.height), float(atlas.height));
    }
    EXPECT_TRUE(exporter::surfaceNormalImage(asset.maps, textures).empty());
}

}  // namespace
}  // namespace subdfit::codec
