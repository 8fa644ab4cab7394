#include "mesh/gltf_materials.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string_view>

#include "io/image_io.h"
#include "util/error.h"
#include "util/hash.h"
#include "util/printable.h"
#include "util/warnings.h"

namespace subdfit::mesh::gltf {
namespace {

constexpr const char* kTextureTransform = "KHR_texture_transform";
constexpr const char* kEmissiveStrength = "KHR_materials_emissive_strength";
constexpr const char* kUnlit = "KHR_materials_unlit";
constexpr const char* kTextureWebp = "EXT_texture_webp";

double number(const tinygltf::Value& v, double fallback) { return v.IsNumber() ? v.GetNumberAsDouble() : fallback; }

std::string shortNumber(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", v);
    return text;
}

Wrap wrapOf(int mode) {
    switch (mode) {
        case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
        case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
        default: return Wrap::Repeat;
    }
}

// KHR_texture_transform: translation · rotation · scale applied to (u, v, 1). glTF's v points
// down, so its "counter-clockwise" rotation is clockwise in a y-up frame: the sign the sample
// implementations and the Khronos sample model use (KhronosGroup/glTF#1563). Numbers that are
// no float (1e300) or no set's index (a texCoord of 1e30) are refused, naming the file.
glm::mat3 textureTransform(const tinygltf::Value& t, int& texCoord, const std::string& path, const char* slot) {
    const tinygltf::Value& offset = t.Get("offset");
    const tinygltf::Value& scale = t.Get("scale");
    const float r = float(number(t.Get("rotation"), 0.0));
    const glm::vec2 o(offset.IsArray() && offset.ArrayLen() == 2 ? number(offset.Get(0), 0.0) : 0.0,
                      offset.IsArray() && offset.ArrayLen() == 2 ? number(offset.Get(1), 0.0) : 0.0);
    const glm::vec2 s(scale.IsArray() && scale.ArrayLen() == 2 ? number(scale.Get(0), 1.0) : 1.0,
                      scale.IsArray() && scale.ArrayLen() == 2 ? number(scale.Get(1), 1.0) : 1.0);
    const std::string where = std::string(slot) + "'s " + kTextureTransform;
    if (!std::isfinite(r + o.x + o.y + s.x + s.y)) throw fileError(path, where + " has a number beyond a float");
    if (t.Has("texCoord")) {
        const double set = number(t.Get("texCoord"), -1.0);
        if (!(set >= 0.0 && set <= 255.0) || set != std::floor(set))
            throw fileError(path, where + " names texture coordinate set " + shortNumber(set) + ", which cannot exist");
        texCoord = int(set);
    }
    const float c = std::cos(r), sn = std::sin(r);
    const glm::mat3 translation(1, 0, 0, 0, 1, 0, o.x, o.y, 1);
    const glm::mat3 rotation(c, -sn, 0, sn, c, 0, 0, 0, 1);
    const glm::mat3 scaling(s.x, 0, 0, 0, s.y, 0, 0, 0, 1);
    return translation * rotation * scaling;
}

class MaterialReader {
public:
    MaterialReader(const tinygltf::Model& model, std::string path) : model_(model), path_(std::move(path)) {}

    MaterialSet read() {
        MaterialSet set;
        for (const tinygltf::Material& m : model_.materials) set.materials.push_back(materialOf(m));
        set.images = decodedImages(set.materials);
        if (!ignored_.empty()) {
            std::string list;
            for (const auto& what : ignored_) list += (list.empty() ? "" : ", ") + what;
            warn(path_ + ": material features not reproduced (the look may differ): " + list);
        }
        return set;
    }

private:
    static constexpr TextureRef Material::*kSlots[] = {&Material::baseColorTexture, &Material::metallicRoughnessTexture,
                                                       &Material::normalTexture, &Material::occlusionTexture,
                                                       &Material::emissiveTexture};

    std::string imageName(int index) const {
        const std::string& uri = model_.images[size_t(index)].uri;
        return path_ + ": " +
               (uri.empty() || uri.rfind("data:", 0) == 0 ? "image " + std::to_string(index)
                                                          : "image '" + printable(uri) + "'");
    }

    // The images the materials use, each decoded once: images with the same bytes (eight naming
    // one file) become one, whose index the textures then share. Every header is read and the
    // pixels counted against the file's budget before the first image is decoded.
    std::vector<Image> decodedImages(std::vector<Material>& materials) const {
        std::vector<Image> images(model_.images.size());
        for (size_t i = 0; i < images.size(); ++i)
            images[i].name = model_.images[i].uri.empty() ? "image " + std::to_string(i) : model_.images[i].uri;
        std::map<int, int> same;  // used image -> the first with its bytes
        std::map<std::pair<std::uint64_t, size_t>, std::vector<int>> byContent;
        for (Material& m : materials)
            for (TextureRef Material::*slot : kSlots) {
                TextureRef& ref = m.*slot;
                if (!ref.present()) continue;
                if (!same.count(ref.image)) {
                    const auto& bytes = model_.images[size_t(ref.image)].image;
                    const std::string_view view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
                    auto& candidates = byContent[{hash64(view), bytes.size()}];
                    int first = ref.image;
                    for (int c : candidates)
                        if (model_.images[size_t(c)].image == bytes) first = c;
                    if (first == ref.image) candidates.push_back(ref.image);
                    same[ref.image] = first;
                }
                ref.image = same[ref.image];
            }
        io::PixelBudget budget;
        std::map<int, io::DecodePlan> toDecode;
        for (const auto& [used, first] : same) {
            if (used != first) continue;
            const auto& bytes = model_.images[size_t(used)].image;
            if (bytes.empty()) {  // tinygltf found no file (or the bufferView is empty)
                warn(imageName(used) + " is missing; the material renders without it");
                continue;
            }
            toDecode[used] = io::planDecode(bytes.data(), bytes.size(), imageName(used), &budget);
        }
        for (const auto& [i, plan] : toDecode) {
            const auto& bytes = model_.images[size_t(i)].image;
            io::DecodedImage decoded = io::decodeImage(bytes.data(), bytes.size(), imageName(i), plan);
            images[size_t(i)].width = decoded.width;
            images[size_t(i)].height = decoded.height;
            images[size_t(i)].rgba = std::move(decoded.rgba);
        }
        return images;
    }

    TextureRef textureOf(int index, int texCoord, const tinygltf::ExtensionMap& extensions, const char* slot) {
        TextureRef ref;
        if (index < 0) return ref;
        if (size_t(index) >= model_.textures.size())
            throw fileError(path_,
                            std::string(slot) + " names texture " + std::to_string(index) + ", which does not exist");
        const tinygltf::Texture& texture = model_.textures[size_t(index)];
        int source = texture.source;
        if (source < 0 && !texture.extensions.empty()) {
            // No fallback image: only the extension's own (gltf-transform's `webp` writes these).
            // WebP is decoded like any other image; other formats (KTX2, AVIF, DDS) are not read.
            const auto webp = texture.extensions.find(kTextureWebp);
            if (webp == texture.extensions.end()) {
                ignored_.insert("texture source extension " + texture.extensions.begin()->first);
                return ref;
            }
            source = int(number(webp->second.Get("source"), -1.0));
        }
        if (source < 0 || size_t(source) >= model_.images.size())
            throw fileError(path_, "texture " + std::to_string(index) + " names image " + std::to_string(source) +
                                       ", which does not exist");
        ref.image = source;
        if (texture.sampler >= 0) {
            if (size_t(texture.sampler) >= model_.samplers.size())
                throw fileError(path_, "texture " + std::to_string(index) + " names sampler " +
                                           std::to_string(texture.sampler) + ", which does not exist");
            const tinygltf::Sampler& sampler = model_.samplers[size_t(texture.sampler)];
            ref.wrapS = wrapOf(sampler.wrapS);
            ref.wrapT = wrapOf(sampler.wrapT);
            ref.nearest = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
        }
        if (const auto t = extensions.find(kTextureTransform); t != extensions.end())
            ref.uvTransform = textureTransform(t->second, texCoord, path_, slot);
        if (texCoord != 0) ignored_.insert(std::string(slot) + " on TEXCOORD_" + std::to_string(texCoord));
        return ref;
    }

    Material materialOf(const tinygltf::Material& m) {
        Material out;
        out.name = m.name;
        const auto& pbr = m.pbrMetallicRoughness;
        if (pbr.baseColorFactor.size() == 4)
            out.baseColorFactor = glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2],
                                            pbr.baseColorFactor[3]);
        out.baseColorTexture = textureOf(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
                                         pbr.baseColorTexture.extensions, "baseColorTexture");
        out.metallicFactor = float(pbr.metallicFactor);
        out.roughnessFactor = float(pbr.roughnessFactor);
        out.metallicRoughnessTexture =
            textureOf(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
                      pbr.metallicRoughnessTexture.extensions, "metallicRoughnessTexture");
        out.normalTexture =
            textureOf(m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions, "normalTexture");
        out.normalScale = float(m.normalTexture.scale);
        out.occlusionTexture = textureOf(m.occlusionTexture.index, m.occlusionTexture.texCoord,
                                         m.occlusionTexture.extensions, "occlusionTexture");
        out.occlusionStrength = float(m.occlusionTexture.strength);
        if (m.emissiveFactor.size() == 3)
            out.emissiveFactor = glm::vec3(m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]);
        out.emissiveTexture = textureOf(m.emissiveTexture.index, m.emissiveTexture.texCoord,
                                        m.emissiveTexture.extensions, "emissiveTexture");
        out.alphaMode = m.alphaMode == "MASK"    ? AlphaMode::Mask
                        : m.alphaMode == "BLEND" ? AlphaMode::Blend
                                                 : AlphaMode::Opaque;
        out.alphaCutoff = float(m.alphaCutoff);
        out.doubleSided = m.doubleSided;
        for (const auto& [name, value] : m.extensions) {
            if (name == kEmissiveStrength) out.emissiveFactor *= float(number(value.Get("emissiveStrength"), 1.0));
            else if (name == kUnlit) out.unlit = true;
            else ignored_.insert(name);
        }
        if (out.alphaMode == AlphaMode::Blend) ignored_.insert("alphaMode BLEND (rendered opaque)");
        if (!std::isfinite(out.baseColorFactor.x + out.baseColorFactor.y + out.baseColorFactor.z +
                           out.baseColorFactor.w + out.metallicFactor + out.roughnessFactor + out.emissiveFactor.x +
                           out.emissiveFactor.y + out.emissiveFactor.z + out.normalScale + out.occlusionStrength))
            throw fileError(path_, "material '" + m.name + "' has a non-finite factor");
        return out;
    }

    const tinygltf::Model& model_;
    std::string path_;
    std::set<std::string> ignored_;
};

}  // namespace

bool keepImageBytes(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes,
                    int size, void*) {
    image->image.assign(bytes, bytes + std::max(size, 0));
    image->width = image->height = image->component = image->bits = 0;
    return true;
}

MaterialSet readMaterials(const tinygltf::Model& model, const std::string& path) {
    return MaterialReader(model, path).read();
}

}  // namespace subdfit::mesh::gltf
