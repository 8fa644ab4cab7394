#pragma once
// A reference asset's appearance, in glTF 2.0's metallic-roughness terms (an OBJ's MTL is read
// into the same form). Factors are linear; images are 8-bit RGBA as the file stores them (sRGB
// for base colour and emissive, linear for the others), top row first.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace subdfit::mesh {

struct Image {
    std::string name;  // for messages: the URI, or "image N"
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // width × height × 4
};

enum class Wrap { Repeat, ClampToEdge, MirroredRepeat };

struct TextureRef {
    int image = -1;  // into MaterialSet::images; -1: no texture
    Wrap wrapS = Wrap::Repeat, wrapT = Wrap::Repeat;
    bool nearest = false;  // magnification filter NEAREST
    // KHR_texture_transform (offset, rotation, scale) as one affine map of (u, v, 1).
    glm::mat3 uvTransform{1.0f};
    bool present() const { return image >= 0; }
};

enum class AlphaMode { Opaque, Mask, Blend };

struct Material {
    std::string name;
    glm::vec4 baseColorFactor{1.0f};
    TextureRef baseColorTexture;
    float metallicFactor = 1.0f, roughnessFactor = 1.0f;
    TextureRef metallicRoughnessTexture;  // G: roughness, B: metallic
    TextureRef normalTexture;
    float normalScale = 1.0f;
    TextureRef occlusionTexture;  // R
    float occlusionStrength = 1.0f;
    glm::vec3 emissiveFactor{0.0f};  // KHR_materials_emissive_strength folded in
    TextureRef emissiveTexture;
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    bool doubleSided = false;
    bool unlit = false;  // KHR_materials_unlit
};

struct MaterialSet {
    std::vector<Material> materials;
    std::vector<Image> images;
};

// glTF's default material (spec 3.9.6): white, fully metallic, fully rough.
inline Material defaultMaterial() {
    Material m;
    m.name = "default";
    return m;
}

}  // namespace subdfit::mesh
