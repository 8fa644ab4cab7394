#include "export/usd/usd_material.h"

#include <algorithm>
#include <cmath>

#include "codec/map_atlas.h"
#include "export/map_images.h"
#include "export/surface_mesh.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

constexpr const char* kHeightCoords = "st";
constexpr const char* kAppearanceCoords = "st1";

// USD's st has its origin at the image's bottom left, glTF's (the atlas's) at its top left.
glm::vec2 usdSt(glm::vec2 gltfUv) { return {gltfUv.x, 1.0f - gltfUv.y}; }

bool hasGeometricMaps(const surface::SurfaceMaps& maps) {
    return maps.layout.resolution > 0 && (maps.hasDisplacement() || maps.hasNormal());
}
bool hasAppearance(const surface::SurfaceMaps& maps) {
    return maps.appearanceLayout.resolution > 0 &&
           (maps.hasBaseColor() || maps.hasMetallicRoughness() || !maps.emissive.empty());
}

// The heights as 16-bit texels over their range, and the scale and bias that undo it.
struct HeightImage {
    std::vector<unsigned char> png;
    float lo = 0.0f, scale = 0.0f;
};

HeightImage heightImage(const surface::SurfaceMaps& maps) {
    const codec::AtlasLayout atlas = codec::atlasLayout(maps.layout);
    const auto [low, high] = std::minmax_element(maps.displacement.begin(), maps.displacement.end());
    HeightImage out;
    out.lo = *low, out.scale = *high - *low;
    // Pixels outside every tile hold height 0 (or the nearest in range): what a coarser mip level
    // blends in at a tile's border is then no height at all.
    std::vector<float> heights = codec::displacementAtlas(atlas, maps);
    std::vector<std::uint16_t> texels(heights.size());
    for (size_t k = 0; k < heights.size(); ++k) {
        const float t = out.scale > 0.0f ? (heights[k] - out.lo) / out.scale : 0.0f;
        texels[k] = std::uint16_t(std::lround(std::clamp(t, 0.0f, 1.0f) * 65535.0f));
    }
    out.png = encodePng(atlas.width, atlas.height, 1, texels.data(), true, "displacement.png");
    return out;
}

// The tangent-space normal map with its y negated: subdfit's bitangent runs along the ptex face's
// v, down the image, where a renderer's runs along st's t, up it.
std::vector<unsigned char> normalMapImage(const surface::SurfaceMaps& maps) {
    surface::SurfaceMaps flipped;
    flipped.layout = maps.layout;
    flipped.normal = maps.normal;
    for (size_t k = 1; k < flipped.normal.size(); k += 2) flipped.normal[k] = -flipped.normal[k];
    return encodeNormalPng(codec::atlasLayout(maps.layout), flipped);
}

// Writes the shaders of one network; paths are absolute, so connections read plainly.
class Network {
public:
    Network(usda::Layer& layer, std::string path, const std::function<std::string(const std::string&)>& assetPath)
        : layer_(layer), path_(std::move(path)), assetPath_(assetPath) {}

    // A UsdPrimvarReader_float2 of `primvar`, named `name`.
    void coordinates(const std::string& name, const std::string& primvar) {
        layer_.block("def Shader " + usda::quoted(name));
        layer_.line("uniform token info:id = \"UsdPrimvarReader_float2\"");
        layer_.line("string inputs:varname = " + usda::quoted(primvar));
        layer_.line("float2 outputs:result");
        layer_.end();
    }

    struct Texture {
        std::string name, file, coordinates, colorSpace;
        glm::vec4 scale{1.0f}, bias{0.0f};
        std::vector<std::string> outputs;  // "float outputs:r", "float3 outputs:rgb", ...
    };
    void texture(const Texture& t, std::vector<unsigned char> bytes) {
        layer_.block("def Shader " + usda::quoted(t.name));
        layer_.line("uniform token info:id = \"UsdUVTexture\"");
        layer_.line("asset inputs:file = @" + assetPath_(t.file) + "@");
        layer_.line("float2 inputs:st.connect = <" + path_ + "/" + t.coordinates + ".outputs:result>");
        layer_.line("token inputs:sourceColorSpace = " + usda::quoted(t.colorSpace));
        layer_.line("token inputs:wrapS = \"clamp\"");
        layer_.line("token inputs:wrapT = \"clamp\"");
        if (t.scale != glm::vec4(1.0f)) layer_.line("float4 inputs:scale = " + usda::tuple(t.scale));
        if (t.bias != glm::vec4(0.0f)) layer_.line("float4 inputs:bias = " + usda::tuple(t.bias));
        for (const std::string& output : t.outputs) layer_.line(output);
        layer_.end();
        files_.push_back({t.file, std::move(bytes)});
    }

    // `type inputs:name = value` on the surface.
    void set(const std::string& type, const std::string& input, const std::string& value) {
        connections_.push_back(type + " inputs:" + input + " = " + value);
    }

    // `type inputs:name.connect = <texture.outputs:output>` on the surface.
    void connect(const std::string& type, const std::string& input, const std::string& texture,
                 const std::string& output) {
        connections_.push_back(type + " inputs:" + input + ".connect = <" + path_ + "/" + texture +
                               ".outputs:" + output + ">");
    }

    void surface(bool displaced) {
        layer_.block("def Shader \"PreviewSurface\"");
        layer_.line("uniform token info:id = \"UsdPreviewSurface\"");
        for (const std::string& line : connections_) layer_.line(line);
        layer_.line("token outputs:surface");
        if (displaced) layer_.line("token outputs:displacement");
        layer_.end();
    }

    std::vector<UsdTextureFile> files() { return std::move(files_); }

private:
    usda::Layer& layer_;
    std::string path_;
    const std::function<std::string(const std::string&)>& assetPath_;
    std::vector<std::string> connections_;
    std::vector<UsdTextureFile> files_;
};

constexpr glm::vec4 kNormalScale{2.0f, 2.0f, 2.0f, 1.0f}, kNormalBias{-1.0f, -1.0f, -1.0f, 0.0f};

}  // namespace

std::vector<UsdTexCoords> usdTexCoords(const surface::SurfaceMaps& maps) {
    std::vector<UsdTexCoords> out;
    if (hasGeometricMaps(maps)) {
        out.push_back({kHeightCoords, [atlas = codec::atlasLayout(maps.layout)](int face, glm::vec2 uv) {
                           return usdSt(codec::atlasUv(atlas, face, uv.x, uv.y));
                       }});
    }
    if (hasAppearance(maps)) {
        if (maps.appearanceAtlas.present())
            out.push_back({kAppearanceCoords, [&atlas = maps.appearanceAtlas](int face, glm::vec2 uv) {
                               return usdSt(surface::atlasUvAt(atlas, face, uv.x, uv.y));
                           }});
        else
            out.push_back(
                {kAppearanceCoords, [atlas = codec::atlasLayout(maps.appearanceLayout)](int face, glm::vec2 uv) {
                     return usdSt(codec::atlasUv(atlas, face, uv.x, uv.y));
                 }});
    }
    return out;
}

bool hasUsdMaterial(const surface::SurfaceMaps& maps) { return hasGeometricMaps(maps) || hasAppearance(maps); }

std::vector<UsdTextureFile> writeMaterialPrim(usda::Layer& layer, const surface::SurfaceMaps& maps,
                                              const std::string& path,
                                              const std::function<std::string(const std::string& name)>& assetPath) {
    SUBDFIT_CHECK(hasUsdMaterial(maps));
    // A normal map on tiles and a normal texture on the reference's atlas never come together
    // (the atlas takes heights alone): one normal input.
    SUBDFIT_CHECK(!(maps.hasNormal() && !maps.normalTexture.empty()));
    const std::string name = path.substr(path.rfind('/') + 1);
    layer.block("def Material " + usda::quoted(name));
    const bool displaced = hasGeometricMaps(maps) && maps.hasDisplacement();
    layer.line("token outputs:surface.connect = <" + path + "/PreviewSurface.outputs:surface>");
    if (displaced)
        layer.line("token outputs:displacement.connect = <" + path + "/PreviewSurface.outputs:displacement>");
    Network network(layer, path, assetPath);

    if (hasGeometricMaps(maps)) {
        network.coordinates("HeightCoords", kHeightCoords);
        if (displaced) {
            HeightImage heights = heightImage(maps);
            network.texture({.name = "Heights",
                             .file = "displacement.png",
                             .coordinates = "HeightCoords",
                             .colorSpace = "raw",
                             .scale = {heights.scale, heights.scale, heights.scale, 1.0f},
                             .bias = {heights.lo, heights.lo, heights.lo, 0.0f},
                             .outputs = {"float outputs:r"}},
                            std::move(heights.png));
            network.connect("float", "displacement", "Heights", "r");
        }
        if (maps.hasNormal()) {
            network.texture({.name = "NormalMap",
                             .file = "normal.png",
                             .coordinates = "HeightCoords",
                             .colorSpace = "raw",
                             .scale = kNormalScale,
                             .bias = kNormalBias,
                             .outputs = {"float3 outputs:rgb"}},
                            normalMapImage(maps));
            network.connect("normal3f", "normal", "NormalMap", "rgb");
        }
    }
    if (hasAppearance(maps)) {
        network.coordinates("AppearanceCoords", kAppearanceCoords);
        const codec::AtlasLayout atlas = codec::atlasLayout(maps.appearanceLayout);
        if (maps.hasBaseColor()) {
            network.texture({.name = "BaseColor",
                             .file = "base_color.png",
                             .coordinates = "AppearanceCoords",
                             .colorSpace = "sRGB",
                             .outputs = {"float3 outputs:rgb"}},
                            encodeAppearancePng(atlas, maps, codec::AppearanceImage::BaseColor));
            network.connect("color3f", "diffuseColor", "BaseColor", "rgb");
        }
        if (maps.hasMetallicRoughness()) {
            const bool occlusion = !maps.occlusion.empty();
            Network::Texture texture{.name = "MetallicRoughness",
                                     .file = "metallic_roughness.png",
                                     .coordinates = "AppearanceCoords",
                                     .colorSpace = "raw",
                                     .outputs = {"float outputs:g", "float outputs:b"}};
            if (occlusion) texture.outputs.insert(texture.outputs.begin(), "float outputs:r");
            network.texture(texture, encodeAppearancePng(atlas, maps, codec::AppearanceImage::MetallicRoughness));
            network.connect("float", "roughness", "MetallicRoughness", "g");
            network.connect("float", "metallic", "MetallicRoughness", "b");
            if (occlusion) network.connect("float", "occlusion", "MetallicRoughness", "r");
        }
        if (!maps.emissive.empty()) {
            network.texture({.name = "Emission",
                             .file = "emissive.png",
                             .coordinates = "AppearanceCoords",
                             .colorSpace = "sRGB",
                             .outputs = {"float3 outputs:rgb"}},
                            encodeAppearancePng(atlas, maps, codec::AppearanceImage::Emissive));
            network.connect("color3f", "emissiveColor", "Emission", "rgb");
        }
        if (!maps.normalTexture.empty()) {
            network.texture({.name = "NormalTexture",
                             .file = "normal_texture.png",
                             .coordinates = "AppearanceCoords",
                             .colorSpace = "raw",
                             .scale = kNormalScale,
                             .bias = kNormalBias,
                             .outputs = {"float3 outputs:rgb"}},
                            encodeAppearancePng(atlas, maps, codec::AppearanceImage::NormalTexture));
            network.connect("normal3f", "normal", "NormalTexture", "rgb");
        }
    }
    if (!maps.hasBaseColor()) {
        // UsdPreviewSurface's own 0.18 would draw darker than the glTF beside it and the reference.
        const auto& grey = SurfaceMaterial{}.baseColorFactor;
        network.set("color3f", "diffuseColor", usda::tuple(glm::vec3(float(grey[0]), float(grey[1]), float(grey[2]))));
    }
    network.surface(displaced);
    layer.end();
    return network.files();
}

}  // namespace subdfit::exporter
