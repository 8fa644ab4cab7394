#include "web_decode.h"

#include <glm/gtc/type_ptr.hpp>

#include "codec/decode_budget.h"
#include "codec/decode_density.h"
#include "export/surface_mesh.h"
#include "util/error.h"
#include "util/warnings.h"

namespace subdfit::web {
namespace {

std::uint32_t roleOf(codec::AppearanceImage which) {
    switch (which) {
        case codec::AppearanceImage::BaseColor: return 0;
        case codec::AppearanceImage::MetallicRoughness: return 1;
        case codec::AppearanceImage::NormalTexture: return 2;
        case codec::AppearanceImage::Emissive: return 3;
    }
    return 0;
}

}  // namespace

std::unique_ptr<Decoded> decode(std::span<const std::uint8_t> bytes, std::int64_t triangles, const std::string& name,
                                codec::SubdEnding ending) {
    auto out = std::make_unique<Decoded>();
    const WarningSink previous = setWarningSink([&](const std::string& line) { out->warnings += line + "\n"; });
    struct Restore {
        const WarningSink& sink;
        ~Restore() { setWarningSink(sink); }
    } restore{previous};

    // Every count the file states, and the triangles to write, priced before they are allocated.
    codec::DecodeBudget budget(name);
    codec::DecodeDensity density;
    codec::ShippedSubd shipped = codec::readShippedSubd(
        bytes, name, &budget,
        [&](const codec::SubdOutline& outline) {
            density = codec::pricedDensity(outline, {.triangles = triangles}, budget);
        },
        ending);
    const codec::SubdAsset& asset = shipped.asset;
    const int segments = density.segments;
    exporter::SurfaceTextures textures{.normalMap = asset.maps.hasNormal()};
    for (const auto& image : shipped.images) {
        using codec::AppearanceImage;
        textures.baseColor |= image.which == AppearanceImage::BaseColor;
        textures.metallicRoughness |= image.which == AppearanceImage::MetallicRoughness;
        textures.occlusion |= image.occlusion;
        textures.normalTexture |= image.which == AppearanceImage::NormalTexture;
        textures.emissive |= image.which == AppearanceImage::Emissive;
    }
    out->mesh = exporter::surfaceGltfMesh(asset.cage, asset.maps, textures, segments);
    if (out->mesh.indices.empty()) throw Error(name + ": nothing to decode: the surface has no triangles");

    // What the glb of `decode` embeds, less the images of an appearance it would not draw.
    out->shipped = std::move(shipped.images);
    for (const auto& image : out->shipped) {
        if (!textures.baseColor) break;  // without a base colour decode draws a grey material
        out->images.push_back({roleOf(image.which), 1, std::uint32_t(image.width), std::uint32_t(image.height),
                               image.bytes.data(), std::uint32_t(image.bytes.size())});
    }
    if (const exporter::NormalImage normal = exporter::surfaceNormalImage(asset.maps, textures); !normal.empty()) {
        // 8 bits a channel, as a browser decodes decode's 16-bit PNG.
        auto& rgba = out->pixels.emplace_back(std::size_t(normal.width) * std::size_t(normal.height) * 4, 255);
        for (std::size_t p = 0; p < rgba.size() / 4; ++p)
            for (int c = 0; c < 3; ++c)
                rgba[4 * p + std::size_t(c)] =
                    std::uint8_t((unsigned(normal.rgb[3 * p + std::size_t(c)]) * 255u + 32767u) / 65535u);
        out->images.push_back(
            {2, 0, std::uint32_t(normal.width), std::uint32_t(normal.height), rgba.data(), std::uint32_t(rgba.size())});
    }

    const exporter::SurfaceMaterial material = exporter::surfaceMaterial(textures);
    Result& r = out->result;
    const exporter::GltfMesh& mesh = out->mesh;
    r.vertexCount = std::uint32_t(mesh.vertexCount());
    r.indexCount = std::uint32_t(mesh.indices.size());
    r.segments = std::uint32_t(segments);
    r.flags = (mesh.hasTangents() ? kTangents : 0) | (textures.baseColor && textures.occlusion ? kOcclusion : 0);
    r.positions = glm::value_ptr(mesh.positions.front());
    r.normals = glm::value_ptr(mesh.normals.front());
    r.tangents = mesh.hasTangents() ? glm::value_ptr(mesh.tangents.front()) : nullptr;
    r.uvs = glm::value_ptr(mesh.uvs.front());
    r.indices = mesh.indices.data();
    for (int c = 0; c < 4; ++c) r.baseColorFactor[c] = float(material.baseColorFactor[std::size_t(c)]);
    r.metallicFactor = float(material.metallicFactor);
    r.roughnessFactor = float(material.roughnessFactor);
    for (int c = 0; c < 3; ++c) r.emissiveFactor[c] = float(material.emissiveFactor[std::size_t(c)]);
    r.imageCount = std::uint32_t(out->images.size());
    r.images = out->images.data();
    r.warnings = out->warnings.c_str();
    return out;
}

}  // namespace subdfit::web
