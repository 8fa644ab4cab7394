#include "export/map_images.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <nlohmann/json.hpp>

#include "util/error.h"
#include "util/printable.h"
#include "util/json_text.h"

// The atlases as files: PNG and EXR through OpenImageIO, and maps.json (the layout and pixel
// functions they encode are in map_atlas.cpp, which decoders without an image library share).
namespace subdfit::exporter {
namespace {

constexpr const char* kDisplacementFile = "displacement.exr";
constexpr const char* kNormalFile = "normal.png";
constexpr const char* kManifestFile = "maps.json";
constexpr const char* kBaseColorFile = "base_color.png";
constexpr const char* kMetallicRoughnessFile = "metallic_roughness.png";
constexpr const char* kNormalTextureFile = "normal_texture.png";
constexpr const char* kEmissiveFile = "emissive.png";

io::WrittenFile writeDisplacementExr(const std::filesystem::path& path, const codec::AtlasLayout& atlas,
                                     const surface::SurfaceMaps& maps, bool half) {
    const std::vector<float> pixels = codec::displacementAtlas(atlas, maps);
    return io::writeOutput(path, [&](const std::filesystem::path& temporary) {
        auto out = OIIO::ImageOutput::create(temporary.string());
        if (!out) throw fileError(path.string(), "no OpenEXR writer in this OpenImageIO build");
        OIIO::ImageSpec spec(atlas.width, atlas.height, 1, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"Y"};
        spec.attribute("compression", "zip");
        spec.attribute("DateTime", "");  // no capture time: the same fit writes the same bytes
        if (!out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
            !out->close())
            throw fileError(path.string(), "could not write image: " + oneLine(out->geterror()));
    });
}

nlohmann::json manifest(const codec::AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                        const AtlasOutputs& outputs) {
    nlohmann::json doc = {
        {"generator", "subdfit"},
        {"resolution", atlas.resolution},
        {"tileSize", atlas.tileSize},
        {"columns", atlas.columns},
        {"rows", atlas.rows},
        {"width", atlas.width},
        {"height", atlas.height},
        {"ptexFaces", atlas.tileOrigins.size()},
        // A formula rather than a list: the list would outweigh a small cage and its maps.
        {"tileOrigin",
         "ptex face f's node (0, 0) is pixel (x0, y0) = (tileSize * (f mod columns), "
         "tileSize * floor(f / columns)); node (i, j) of the face is pixel (x0 + i, y0 + j), "
         "i along u, j along v, image row 0 at the top"},
        {"uv",
         "texcoord of ptex (u, v) in [0,1]^2 on face f: ((x0 + 0.5 + u * resolution) / width, "
         "(y0 + 0.5 + v * resolution) / height), v down the image as in glTF; sample bilinearly "
         "without mipmaps to reproduce the fitted node interpolation exactly"},
    };
    if (maps.hasDisplacement() && outputs.displacement)
        doc["displacement"] = {{"file", kDisplacementFile},
                               {"channel", "Y"},
                               {"units", "cage units, along the unit normal of the limit surface"},
                               {"shading", maps.shadingNormal == surface::ShadingNormal::Limit
                                               ? "the limit surface's normal shades the displaced surface"
                                               : "the displaced surface's own normal"}};
    if (maps.hasNormal() && outputs.normal)
        doc["normal"] = {
            {"file", kNormalFile},
            {"encoding", outputs.compact ? "8-bit RGB, rgb = n * 0.5 + 0.5" : "16-bit RGB, rgb = n * 0.5 + 0.5"},
            {"space",
             "tangent space of the limit surface: x along dP/du, y along dP/dv, z along "
             "N = normalize(cross(dP/du, dP/dv)); n = normalize(x, y, 1)"}};
    return doc;
}

}  // namespace

std::vector<unsigned char> encodePng(int width, int height, int channels, const void* pixels, bool sixteenBit,
                                     const std::string& name) {
    const OIIO::TypeDesc type = sixteenBit ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    auto out = OIIO::ImageOutput::create("png");
    if (!out || !out->supports("ioproxy")) throw Error(name + ": no in-memory PNG writer in this OpenImageIO build");
    OIIO::ImageSpec spec(width, height, channels, type);
    if (!out->set_ioproxy(&proxy) || !out->open(name, spec) || !out->write_image(type, pixels) || !out->close())
        throw Error(name + ": could not encode PNG: " + oneLine(out->geterror()));
    return bytes;
}

std::vector<unsigned char> encodeNormalPng(const codec::AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                           bool eightBit) {
    const std::vector<std::uint16_t> pixels = codec::normalAtlas(atlas, maps);
    if (!eightBit) return encodePng(atlas.width, atlas.height, 3, pixels.data(), true, kNormalFile);
    std::vector<std::uint8_t> pixels8;
    for (std::uint16_t p : pixels) pixels8.push_back(std::uint8_t((unsigned(p) * 255u + 32767u) / 65535u));
    return encodePng(atlas.width, atlas.height, 3, pixels8.data(), false, kNormalFile);
}

std::vector<unsigned char> encodeAppearancePng(const codec::AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                               codec::AppearanceImage which) {
    const auto pixels = codec::appearancePixels(atlas, maps, which);
    const char* names[] = {kBaseColorFile, kMetallicRoughnessFile, kNormalTextureFile, kEmissiveFile};
    return encodePng(atlas.width, atlas.height, 3, pixels.data(), false, names[int(which)]);
}

std::vector<io::WrittenFile> writeMapAtlases(const std::filesystem::path& dir, const surface::SurfaceMaps& maps,
                                             const AtlasOutputs& outputs) {
    std::vector<io::WrittenFile> written;
    nlohmann::json doc;
    if (maps.layout.resolution > 0) {
        const codec::AtlasLayout atlas = codec::atlasLayout(maps.layout);
        if (maps.hasDisplacement() && outputs.displacement)
            written.push_back(writeDisplacementExr(dir / kDisplacementFile, atlas, maps, outputs.compact));
        if (maps.hasNormal() && outputs.normal)
            written.push_back(io::writeBytes(dir / kNormalFile, encodeNormalPng(atlas, maps, outputs.compact)));
        doc = manifest(atlas, maps, outputs);
    }
    if (maps.appearanceLayout.resolution > 0) {
        const codec::AtlasLayout atlas = codec::atlasLayout(maps.appearanceLayout);
        nlohmann::json appearance = manifest(atlas, {}, outputs);
        appearance.erase("generator");
        if (maps.appearanceAtlas.present()) {
            // Not tiles: the reference's own texture space, placed by the corners' coordinates.
            appearance = {{"width", atlas.width},
                          {"height", atlas.height},
                          {"uv",
                           "the reference's texture coordinates (glTF convention); ptex (u, v) of face f maps to "
                           "the bilinear blend of its corners' coordinates, stored in asset.subd's AUVS section; "
                           "sample bilinearly, clamped to the edge"}};
        }
        if (maps.hasBaseColor()) {
            written.push_back(io::writeBytes(dir / kBaseColorFile,
                                             encodeAppearancePng(atlas, maps, codec::AppearanceImage::BaseColor)));
            appearance["baseColor"] = {{"file", kBaseColorFile},
                                       {"encoding", "8-bit sRGB RGB, as glTF's baseColorTexture"}};
        }
        if (maps.hasMetallicRoughness()) {
            written.push_back(
                io::writeBytes(dir / kMetallicRoughnessFile,
                               encodeAppearancePng(atlas, maps, codec::AppearanceImage::MetallicRoughness)));
            appearance["metallicRoughness"] = {
                {"file", kMetallicRoughnessFile},
                {"encoding", "8-bit RGB, G roughness, B metallic, as glTF's metallicRoughnessTexture"}};
        }
        if (!maps.occlusion.empty()) appearance["occlusion"] = {{"file", kMetallicRoughnessFile}, {"channel", "R"}};
        if (!maps.normalTexture.empty()) {
            written.push_back(io::writeBytes(dir / kNormalTextureFile,
                                             encodeAppearancePng(atlas, maps, codec::AppearanceImage::NormalTexture)));
            appearance["normalTexture"] = {
                {"file", kNormalTextureFile},
                {"encoding", "8-bit RGB as glTF's normalTexture, in the atlas coordinates' tangent frame"}};
        }
        if (!maps.emissive.empty()) {
            written.push_back(io::writeBytes(dir / kEmissiveFile,
                                             encodeAppearancePng(atlas, maps, codec::AppearanceImage::Emissive)));
            appearance["emissive"] = {{"file", kEmissiveFile},
                                      {"encoding", "8-bit sRGB RGB, as glTF's emissiveTexture"}};
        }
        doc["generator"] = "subdfit";
        doc["appearance"] = appearance;
    }
    if (outputs.manifest && !doc.is_null()) {
        const std::string text = jsonText(doc, 2);
        written.push_back(
            io::writeBytes(dir / kManifestFile, {reinterpret_cast<const unsigned char*>(text.data()), text.size()}));
    }
    return written;
}

}  // namespace subdfit::exporter
