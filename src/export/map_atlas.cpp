#include "export/map_atlas.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>

#include "util/error.h"

namespace subdfit::exporter {
namespace {

constexpr const char* kDisplacementFile = "displacement.exr";
constexpr const char* kNormalFile = "normal.png";
constexpr const char* kManifestFile = "maps.json";
constexpr const char* kBaseColorFile = "base_color.png";
constexpr const char* kMetallicRoughnessFile = "metallic_roughness.png";
constexpr const char* kNormalTextureFile = "normal_texture.png";
constexpr const char* kEmissiveFile = "emissive.png";

void checkMaps(const surface::TexelLayout& layout, const surface::SurfaceMaps& maps) {
    if (&layout == &maps.appearanceLayout) {
        SUBDFIT_CHECK(layout.resolution >= 1 && layout.ptexFaceCount >= 1);
        SUBDFIT_CHECK(maps.baseColor.empty() || maps.baseColor.size() == 3 * size_t(layout.nodeCount));
        SUBDFIT_CHECK(maps.metallicRoughness.empty() || maps.metallicRoughness.size() == 2 * size_t(layout.nodeCount));
        return;
    }
    SUBDFIT_CHECK(layout.resolution >= 1 && layout.ptexFaceCount >= 1);
    SUBDFIT_CHECK(layout.faceNodes.size() == size_t(layout.ptexFaceCount) * size_t(layout.nodesPerFace()));
    SUBDFIT_CHECK(maps.displacement.empty() || maps.displacement.size() == size_t(layout.nodeCount));
    SUBDFIT_CHECK(maps.normal.empty() || maps.normal.size() == 2 * size_t(layout.nodeCount));
}

// Visits every tile pixel as (pixel index, node).
template <typename Visit>
void forEachTilePixel(const AtlasLayout& atlas, const surface::TexelLayout& layout, Visit visit) {
    for (int face = 0; face < layout.ptexFaceCount; ++face) {
        const glm::ivec2 origin = atlas.tileOrigins[size_t(face)];
        for (int j = 0; j <= layout.resolution; ++j)
            for (int i = 0; i <= layout.resolution; ++i)
                visit(size_t(origin.y + j) * size_t(atlas.width) + size_t(origin.x + i), layout.node(face, i, j));
    }
}

std::uint16_t unorm16(float value) {
    return std::uint16_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 65535.0f));
}

WrittenFile writeDisplacementExr(const std::filesystem::path& path, const AtlasLayout& atlas,
                                 const surface::SurfaceMaps& maps, bool half) {
    const std::vector<float> pixels = displacementAtlas(atlas, maps);
    return writeOutput(path, [&](const std::filesystem::path& temporary) {
        auto out = OIIO::ImageOutput::create(temporary.string());
        if (!out) throw fileError(path.string(), "no OpenEXR writer in this OpenImageIO build");
        OIIO::ImageSpec spec(atlas.width, atlas.height, 1, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
        spec.channelnames = {"Y"};
        spec.attribute("compression", "zip");
        spec.attribute("DateTime", "");  // no capture time: the same fit writes the same bytes
        if (!out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) ||
            !out->close())
            throw fileError(path.string(), "could not write image: " + out->geterror());
    });
}

nlohmann::json manifest(const AtlasLayout& atlas, const surface::SurfaceMaps& maps, const AtlasOutputs& outputs) {
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
        {"tileOrigin", "ptex face f's node (0, 0) is pixel (x0, y0) = (tileSize * (f mod columns), "
                       "tileSize * floor(f / columns)); node (i, j) of the face is pixel (x0 + i, y0 + j), "
                       "i along u, j along v, image row 0 at the top"},
        {"uv", "texcoord of ptex (u, v) in [0,1]^2 on face f: ((x0 + 0.5 + u * resolution) / width, "
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
        doc["normal"] = {{"file", kNormalFile},
                         {"encoding", outputs.compact ? "8-bit RGB, rgb = n * 0.5 + 0.5" : "16-bit RGB, rgb = n * 0.5 + 0.5"},
                         {"space", "tangent space of the limit surface: x along dP/du, y along dP/dv, z along "
                                   "N = normalize(cross(dP/du, dP/dv)); n = normalize(x, y, 1)"}};
    return doc;
}

}  // namespace

AtlasLayout atlasLayout(const surface::TexelLayout& layout) {
    SUBDFIT_CHECK(layout.resolution >= 1 && layout.ptexFaceCount >= 1);
    AtlasLayout atlas;
    atlas.resolution = layout.resolution;
    atlas.tileSize = layout.resolution + 1;
    // Integer ceil(sqrt(F)): a float sqrt can land just below an exact square.
    while (atlas.columns * atlas.columns < layout.ptexFaceCount) ++atlas.columns;
    atlas.rows = (layout.ptexFaceCount + atlas.columns - 1) / atlas.columns;
    atlas.width = atlas.columns * atlas.tileSize;
    atlas.height = atlas.rows * atlas.tileSize;
    atlas.tileOrigins.reserve(size_t(layout.ptexFaceCount));
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        atlas.tileOrigins.emplace_back(face % atlas.columns * atlas.tileSize, face / atlas.columns * atlas.tileSize);
    return atlas;
}

glm::vec2 atlasUv(const AtlasLayout& atlas, int face, float u, float v) {
    const glm::ivec2 origin = atlas.tileOrigins[size_t(face)];
    const float t = float(atlas.resolution);
    return {(float(origin.x) + 0.5f + u * t) / float(atlas.width), (float(origin.y) + 0.5f + v * t) / float(atlas.height)};
}

std::vector<float> displacementAtlas(const AtlasLayout& atlas, const surface::SurfaceMaps& maps) {
    checkMaps(maps.layout, maps);
    SUBDFIT_CHECK(maps.hasDisplacement());
    std::vector<float> pixels(size_t(atlas.width) * size_t(atlas.height), 0.0f);
    forEachTilePixel(atlas, maps.layout, [&](size_t pixel, int node) { pixels[pixel] = maps.displacement[size_t(node)]; });
    return pixels;
}

std::vector<std::uint16_t> normalAtlas(const AtlasLayout& atlas, const surface::SurfaceMaps& maps) {
    checkMaps(maps.layout, maps);
    SUBDFIT_CHECK(maps.hasNormal());
    const std::uint16_t half = unorm16(0.5f), one = unorm16(1.0f);
    std::vector<std::uint16_t> pixels;
    pixels.reserve(size_t(atlas.width) * size_t(atlas.height) * 3);
    for (size_t p = 0; p < size_t(atlas.width) * size_t(atlas.height); ++p) pixels.insert(pixels.end(), {half, half, one});
    forEachTilePixel(atlas, maps.layout, [&](size_t pixel, int node) {
        const float x = maps.normal[2 * size_t(node)], y = maps.normal[2 * size_t(node) + 1];
        const float scale = 1.0f / std::sqrt(x * x + y * y + 1.0f);
        const float n[3] = {x * scale, y * scale, scale};
        for (int c = 0; c < 3; ++c) pixels[3 * pixel + size_t(c)] = unorm16(n[c] * 0.5f + 0.5f);
    });
    return pixels;
}

std::vector<unsigned char> encodePng(int width, int height, int channels, const void* pixels, bool sixteenBit,
                                     const std::string& name) {
    const OIIO::TypeDesc type = sixteenBit ? OIIO::TypeDesc::UINT16 : OIIO::TypeDesc::UINT8;
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    auto out = OIIO::ImageOutput::create("png");
    if (!out || !out->supports("ioproxy")) throw Error(name + ": no in-memory PNG writer in this OpenImageIO build");
    OIIO::ImageSpec spec(width, height, channels, type);
    if (!out->set_ioproxy(&proxy) || !out->open(name, spec) || !out->write_image(type, pixels) || !out->close())
        throw Error(name + ": could not encode PNG: " + out->geterror());
    return bytes;
}

std::vector<unsigned char> encodeNormalPng(const AtlasLayout& atlas, const surface::SurfaceMaps& maps, bool eightBit) {
    const std::vector<std::uint16_t> pixels = normalAtlas(atlas, maps);
    if (!eightBit) return encodePng(atlas.width, atlas.height, 3, pixels.data(), true, kNormalFile);
    std::vector<std::uint8_t> pixels8;
    for (std::uint16_t p : pixels) pixels8.push_back(std::uint8_t((unsigned(p) * 255u + 32767u) / 65535u));
    return encodePng(atlas.width, atlas.height, 3, pixels8.data(), false, kNormalFile);
}

std::vector<unsigned char> encodeAppearancePng(const AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                               AppearanceImage which) {
    const auto pixels = appearancePixels(atlas, maps, which);
    const char* names[] = {kBaseColorFile, kMetallicRoughnessFile, kNormalTextureFile, kEmissiveFile};
    return encodePng(atlas.width, atlas.height, 3, pixels.data(), false, names[int(which)]);
}

namespace {

// How an appearance image holds its values: `channels` floats per node in the pixel's channels
// from `first` on, and what a pixel outside every tile holds.
struct ImageChannels {
    int channels, first;
    std::array<std::uint8_t, 3> fill;
};

ImageChannels imageChannels(AppearanceImage which) {
    switch (which) {
        case AppearanceImage::BaseColor: return {3, 0, {128, 128, 128}};
        case AppearanceImage::MetallicRoughness: return {2, 1, {255, 255, 0}};
        case AppearanceImage::NormalTexture: return {3, 0, {128, 128, 255}};
        case AppearanceImage::Emissive: return {3, 0, {0, 0, 0}};
    }
    throw Error("unknown appearance image");
}

const std::vector<float>& imageValues(const surface::SurfaceMaps& maps, AppearanceImage which) {
    switch (which) {
        case AppearanceImage::BaseColor: return maps.baseColor;
        case AppearanceImage::MetallicRoughness: return maps.metallicRoughness;
        case AppearanceImage::NormalTexture: return maps.normalTexture;
        case AppearanceImage::Emissive: return maps.emissive;
    }
    throw Error("unknown appearance image");
}

// Node values as the mean of every pixel that holds the node, from `channels` pixel channels
// starting at `first`.
std::vector<float> nodesFromPixels(const AtlasLayout& atlas, const surface::TexelLayout& layout,
                                   std::span<const std::uint8_t> rgb, int first, int channels) {
    SUBDFIT_CHECK(rgb.size() == size_t(atlas.width) * size_t(atlas.height) * 3);
    std::vector<float> sums(size_t(layout.nodeCount) * size_t(channels), 0.0f);
    std::vector<int> counts(size_t(layout.nodeCount), 0);
    forEachTilePixel(atlas, layout, [&](size_t pixel, int node) {
        const std::uint8_t* p = &rgb[3 * pixel];
        for (int c = 0; c < channels; ++c) sums[size_t(node) * size_t(channels) + size_t(c)] += float(p[first + c]) / 255.0f;
        ++counts[size_t(node)];
    });
    for (size_t n = 0; n < counts.size(); ++n)
        for (int c = 0; c < channels; ++c) sums[n * size_t(channels) + size_t(c)] /= float(std::max(1, counts[n]));
    return sums;
}

}  // namespace

std::vector<std::uint8_t> appearancePixels(const AtlasLayout& atlas, const surface::SurfaceMaps& maps,
                                           AppearanceImage which) {
    checkMaps(maps.appearanceLayout, maps);
    const ImageChannels image = imageChannels(which);
    const std::vector<float>& values = imageValues(maps, which);
    SUBDFIT_CHECK(values.size() == size_t(maps.appearanceLayout.nodeCount) * size_t(image.channels));
    const bool occlusion = which == AppearanceImage::MetallicRoughness && !maps.occlusion.empty();
    std::vector<std::uint8_t> pixels(size_t(atlas.width) * size_t(atlas.height) * 3, 0);
    for (size_t p = 0; p < pixels.size(); p += 3) std::copy(image.fill.begin(), image.fill.end(), pixels.begin() + std::ptrdiff_t(p));
    auto unorm8 = [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    forEachTilePixel(atlas, maps.appearanceLayout, [&](size_t pixel, int node) {
        std::uint8_t* p = &pixels[3 * pixel];
        const size_t n = size_t(node);
        for (int c = 0; c < image.channels; ++c) p[image.first + c] = unorm8(values[size_t(image.channels) * n + size_t(c)]);
        if (occlusion) p[0] = unorm8(maps.occlusion[n]);
    });
    return pixels;
}

std::vector<float> nodesFromAppearancePixels(const AtlasLayout& atlas, const surface::TexelLayout& layout,
                                             std::span<const std::uint8_t> rgb, AppearanceImage which) {
    const ImageChannels image = imageChannels(which);
    return nodesFromPixels(atlas, layout, rgb, image.first, image.channels);
}

std::vector<float> occlusionFromPixels(const AtlasLayout& atlas, const surface::TexelLayout& layout,
                                       std::span<const std::uint8_t> rgb) {
    return nodesFromPixels(atlas, layout, rgb, 0, 1);
}

surface::SurfaceMaps normalOnAppearanceLattice(const surface::SurfaceMaps& maps) {
    surface::SurfaceMaps out;
    out.layout = maps.appearanceLayout;
    if (!maps.hasNormal()) return out;
    const surface::TexelLayout& to = maps.appearanceLayout;
    out.normal.assign(2 * size_t(to.nodeCount), 0.0f);
    const float t = float(to.resolution);
    for (int f = 0; f < to.ptexFaceCount; ++f)
        for (int j = 0; j <= to.resolution; ++j)
            for (int i = 0; i <= to.resolution; ++i) {
                const size_t n = size_t(to.node(f, i, j));
                for (int c = 0; c < 2; ++c)
                    out.normal[2 * n + size_t(c)] =
                        surface::sampleBilinear(maps.layout, maps.normal, 2, c, f, float(i) / t, float(j) / t);
            }
    return out;
}

std::vector<WrittenFile> writeMapAtlases(const std::filesystem::path& dir, const surface::SurfaceMaps& maps,
                                         const AtlasOutputs& outputs) {
    std::vector<WrittenFile> written;
    nlohmann::json doc;
    if (maps.layout.resolution > 0) {
        const AtlasLayout atlas = atlasLayout(maps.layout);
        checkMaps(maps.layout, maps);
        if (maps.hasDisplacement() && outputs.displacement)
            written.push_back(writeDisplacementExr(dir / kDisplacementFile, atlas, maps, outputs.compact));
        if (maps.hasNormal() && outputs.normal)
            written.push_back(writeBytes(dir / kNormalFile, encodeNormalPng(atlas, maps, outputs.compact)));
        doc = manifest(atlas, maps, outputs);
    }
    if (maps.appearanceLayout.resolution > 0) {
        const AtlasLayout atlas = atlasLayout(maps.appearanceLayout);
        nlohmann::json appearance = manifest(atlas, {}, outputs);
        appearance.erase("generator");
        if (maps.appearanceAtlas.present()) {
            // Not tiles: the reference's own texture space, placed by the corners' coordinates.
            appearance = {{"width", atlas.width}, {"height", atlas.height},
                          {"uv", "the reference's texture coordinates (glTF convention); ptex (u, v) of face f maps to "
                                 "the bilinear blend of its corners' coordinates, stored in asset.subd's AUVS section; "
                                 "sample bilinearly, clamped to the edge"}};
        }
        if (maps.hasBaseColor()) {
            written.push_back(writeBytes(dir / kBaseColorFile, encodeAppearancePng(atlas, maps, AppearanceImage::BaseColor)));
            appearance["baseColor"] = {{"file", kBaseColorFile}, {"encoding", "8-bit sRGB RGB, as glTF's baseColorTexture"}};
        }
        if (maps.hasMetallicRoughness()) {
            written.push_back(writeBytes(dir / kMetallicRoughnessFile,
                                         encodeAppearancePng(atlas, maps, AppearanceImage::MetallicRoughness)));
            appearance["metallicRoughness"] = {{"file", kMetallicRoughnessFile},
                                               {"encoding", "8-bit RGB, G roughness, B metallic, as glTF's metallicRoughnessTexture"}};
        }
        if (!maps.occlusion.empty()) appearance["occlusion"] = {{"file", kMetallicRoughnessFile}, {"channel", "R"}};
        if (!maps.normalTexture.empty()) {
            written.push_back(writeBytes(dir / kNormalTextureFile, encodeAppearancePng(atlas, maps, AppearanceImage::NormalTexture)));
            appearance["normalTexture"] = {{"file", kNormalTextureFile},
                                           {"encoding", "8-bit RGB as glTF's normalTexture, in the atlas coordinates' tangent frame"}};
        }
        if (!maps.emissive.empty()) {
            written.push_back(writeBytes(dir / kEmissiveFile, encodeAppearancePng(atlas, maps, AppearanceImage::Emissive)));
            appearance["emissive"] = {{"file", kEmissiveFile}, {"encoding", "8-bit sRGB RGB, as glTF's emissiveTexture"}};
        }
        doc["generator"] = "subdfit";
        doc["appearance"] = appearance;
    }
    if (outputs.manifest && !doc.is_null()) {
        const std::string text = doc.dump(2) + "\n";
        written.push_back(writeBytes(dir / kManifestFile, {reinterpret_cast<const unsigned char*>(text.data()), text.size()}));
    }
    return written;
}

}  // namespace subdfit::exporter
