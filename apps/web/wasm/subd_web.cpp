// The web decoder's entry points: asset.subd bytes in, the surface `subdfit decode` writes out as
// arrays, through the same reader (readShippedSubd), density choice (decodeSegments) and surface
// (surfaceGltfMesh, surfaceNormalImage, surfaceMaterial). Appearance images stay the JPEGs the
// file carries: the browser decodes them. apps/web/js/subd_core.mjs reads the Result.
#include <emscripten/emscripten.h>

#include <glm/gtc/type_ptr.hpp>

#include <cstdint>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <unordered_map>
#include <vector>

#include "export/subd_decode.h"
#include "export/subd_format.h"
#include "export/surface_mesh.h"
#include "util/error.h"
#include "util/warnings.h"

namespace {

using namespace subdfit;

// An image of the material. Roles: 0 base colour, 1 metallic-roughness (its red channel the
// occlusion when Result::flags says so), 2 normal, 3 emissive.
struct Image {
    std::uint32_t role, encoding;  // encoding 0: RGBA8 pixels, rows top first; 1: JPEG bytes
    std::uint32_t width, height;
    const std::uint8_t* data;
    std::uint32_t size;
};

// Read word by word (4 bytes each) by subd_core.mjs: keep the two in step.
struct Result {
    std::uint32_t vertexCount, indexCount, segments, flags;  // flags: 1 tangents, 2 occlusion
    const float *positions, *normals, *tangents, *uvs;
    const std::uint32_t* indices;
    float baseColorFactor[4], metallicFactor, roughnessFactor, emissiveFactor[3];
    std::uint32_t imageCount;
    const Image* images;
    const char* warnings;  // '\n'-separated, empty when none
};
static_assert(sizeof(Result) == 21 * 4, "subd_core.mjs reads Result as 21 words");
static_assert(sizeof(Image) == 6 * 4, "subd_core.mjs reads Image as 6 words");

constexpr std::uint32_t kTangents = 1, kOcclusion = 2;

struct Decoded {
    Result result{};
    exporter::GltfMesh mesh;
    std::vector<Image> images;
    std::vector<std::vector<std::uint8_t>> pixels;
    std::vector<exporter::ShippedImage> shipped;
    std::string warnings;
};

std::string lastError;
std::unordered_map<const Result*, std::unique_ptr<Decoded>> live;  // until subd_free

std::uint32_t roleOf(exporter::AppearanceImage which) {
    switch (which) {
        case exporter::AppearanceImage::BaseColor: return 0;
        case exporter::AppearanceImage::MetallicRoughness: return 1;
        case exporter::AppearanceImage::NormalTexture: return 2;
        case exporter::AppearanceImage::Emissive: return 3;
    }
    return 0;
}

std::unique_ptr<Decoded> decode(std::span<const std::uint8_t> bytes, std::uint64_t triangles, const std::string& name) {
    auto out = std::make_unique<Decoded>();
    const WarningSink previous = setWarningSink([&](const std::string& line) { out->warnings += line + "\n"; });
    struct Restore {
        const WarningSink& sink;
        ~Restore() { setWarningSink(sink); }
    } restore{previous};

    exporter::ShippedSubd shipped = exporter::readShippedSubd(bytes, name);
    const exporter::SubdAsset& asset = shipped.asset;
    const int segments = exporter::decodeSegments(asset, {.triangles = triangles}, name);
    exporter::SurfaceTextures textures{.normalMap = asset.maps.hasNormal()};
    for (const auto& image : shipped.images) {
        using exporter::AppearanceImage;
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
            for (int c = 0; c < 3; ++c) rgba[4 * p + std::size_t(c)] = std::uint8_t((unsigned(normal.rgb[3 * p + std::size_t(c)]) * 255u + 32767u) / 65535u);
        out->images.push_back({2, 0, std::uint32_t(normal.width), std::uint32_t(normal.height), rgba.data(),
                               std::uint32_t(rgba.size())});
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

}  // namespace

extern "C" {

// The decoded surface, or null with subd_error() saying why in one line. `triangles` 0: the
// default density; `name` (UTF-8) names the file in messages.
EMSCRIPTEN_KEEPALIVE Result* subd_decode(const std::uint8_t* bytes, std::uint32_t size, double triangles, const char* name) {
    try {
        if (!(triangles >= 0.0) || triangles > double(subdfit::exporter::kMaxDecodeTriangles))
            throw subdfit::Error("invalid option: triangles: must be in 0.." + std::to_string(subdfit::exporter::kMaxDecodeTriangles));
        auto decoded = decode({bytes, size}, std::uint64_t(triangles), name);
        Result* result = &decoded->result;
        live.emplace(result, std::move(decoded));
        return result;
    } catch (const std::bad_alloc&) {
        lastError = std::string(name) + ": out of memory (the web decoder stops at 2 GiB)";
    } catch (const std::exception& e) {
        lastError = e.what();
    }
    return nullptr;
}

EMSCRIPTEN_KEEPALIVE const char* subd_error() { return lastError.c_str(); }

EMSCRIPTEN_KEEPALIVE void subd_free(Result* result) { live.erase(result); }

}
