#include "codec/map_atlas.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "util/error.h"

namespace subdfit::codec {
namespace {

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

std::uint16_t unorm16(float value) { return std::uint16_t(std::lround(std::clamp(value, 0.0f, 1.0f) * 65535.0f)); }
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
    return {(float(origin.x) + 0.5f + u * t) / float(atlas.width),
            (float(origin.y) + 0.5f + v * t) / float(atlas.height)};
}

std::vector<float> displacementAtlas(const AtlasLayout& atlas, const surface::SurfaceMaps& maps) {
    checkMaps(maps.layout, maps);
    SUBDFIT_CHECK(maps.hasDisplacement());
    std::vector<float> pixels(size_t(atlas.width) * size_t(atlas.height), 0.0f);
    forEachTilePixel(atlas, maps.layout,
                     [&](size_t pixel, int node) { pixels[pixel] = maps.displacement[size_t(node)]; });
    return pixels;
}

std::vector<std::uint16_t> normalAtlas(const AtlasLayout& atlas, const surface::SurfaceMaps& maps) {
    checkMaps(maps.layout, maps);
    SUBDFIT_CHECK(maps.hasNormal());
    const std::uint16_t half = unorm16(0.5f), one = unorm16(1.0f);
    std::vector<std::uint16_t> pixels;
    pixels.reserve(size_t(atlas.width) * size_t(atlas.height) * 3);
    for (size_t p = 0; p < size_t(atlas.width) * size_t(atlas.height); ++p)
        pixels.insert(pixels.end(), {half, half, one});
    forEachTilePixel(atlas, maps.layout, [&](size_t pixel, int node) {
        const float x = maps.normal[2 * size_t(node)], y = maps.normal[2 * size_t(node) + 1];
        const float scale = 1.0f / std::sqrt(x * x + y * y + 1.0f);
        const float n[3] = {x * scale, y * scale, scale};
        for (int c = 0; c < 3; ++c) pixels[3 * pixel + size_t(c)] = unorm16(n[c] * 0.5f + 0.5f);
    });
    return pixels;
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
        for (int c = 0; c < channels; ++c)
            sums[size_t(node) * size_t(channels) + size_t(c)] += float(p[first + c]) / 255.0f;
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
    for (size_t p = 0; p < pixels.size(); p += 3)
        std::copy(image.fill.begin(), image.fill.end(), pixels.begin() + std::ptrdiff_t(p));
    auto unorm8 = [](float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); };
    forEachTilePixel(atlas, maps.appearanceLayout, [&](size_t pixel, int node) {
        std::uint8_t* p = &pixels[3 * pixel];
        const size_t n = size_t(node);
        for (int c = 0; c < image.channels; ++c)
            p[image.first + c] = unorm8(values[size_t(image.channels) * n + size_t(c)]);
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

}  // namespace subdfit::codec
