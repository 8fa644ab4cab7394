#include "export/gltf/textured_glb.h"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>

#include <glm/common.hpp>

#include "export/gltf/draco_encoding.h"
#include "export/gltf/glb_container.h"
#include "export/gltf/gltf_builder.h"
#include "export/gltf_mesh.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

using nlohmann::json;
using namespace gltf;

int wrapEnum(mesh::Wrap wrap) {
    switch (wrap) {
        case mesh::Wrap::ClampToEdge: return kClampToEdge;
        case mesh::Wrap::MirroredRepeat: return kMirroredRepeat;
        case mesh::Wrap::Repeat: break;
    }
    return kRepeat;
}

// One material's triangles as a mesh of their own (vertices renumbered).
GltfMesh primitiveOf(const mesh::PolygonMesh& triangles, const std::vector<glm::vec3>& normals, int material,
                     const glm::mat3& uvTransform, glm::ivec2 imageSize) {
    GltfMesh out;
    out.atlasSize = imageSize;
    std::vector<std::uint32_t> remap(triangles.positions.size(), std::numeric_limits<std::uint32_t>::max());
    for (int f = 0; f < triangles.faceCount(); ++f) {
        if (triangles.faceMaterials[size_t(f)] != material) continue;
        for (int k = 0; k < 3; ++k) {
            const auto v = size_t(triangles.faceIndices[size_t(3 * f + k)]);
            if (remap[v] == std::numeric_limits<std::uint32_t>::max()) {
                remap[v] = std::uint32_t(out.positions.size());
                out.positions.push_back(triangles.positions[v]);
                if (!normals.empty()) out.normals.push_back(normals[v]);
                if (!triangles.uvs.empty())
                    out.uvs.push_back(glm::vec2(uvTransform * glm::vec3(triangles.uvs[v], 1.0f)));
            }
            out.indices.push_back(remap[v]);
        }
    }
    return out;
}

// POSITION, NORMAL (when there are normals) and TEXCOORD_0 (when there are uvs) at consecutive
// accessors from `first`.
json attributesFrom(size_t first, bool normals, bool uvs) {
    json attributes = {{"POSITION", first}};
    if (normals) attributes["NORMAL"] = ++first;
    if (uvs) attributes["TEXCOORD_0"] = ++first;
    return attributes;
}

class TexturedDocument {
public:
    explicit TexturedDocument(const std::vector<EncodedImage>& images) : images_(images) {}

    // The material's JSON, adding the textures it names.
    json material(const mesh::Material& m) {
        json pbr = {
            {"baseColorFactor", {m.baseColorFactor.r, m.baseColorFactor.g, m.baseColorFactor.b, m.baseColorFactor.a}},
            {"metallicFactor", m.metallicFactor},
            {"roughnessFactor", m.roughnessFactor}};
        json out = {{"name", m.name.empty() ? "material" : m.name}, {"doubleSided", m.doubleSided}};
        if (auto t = texture(m.baseColorTexture)) pbr["baseColorTexture"] = *t;
        if (auto t = texture(m.metallicRoughnessTexture)) pbr["metallicRoughnessTexture"] = *t;
        if (auto t = texture(m.normalTexture))
            out["normalTexture"] = {{"index", (*t)["index"]}, {"scale", m.normalScale}};
        if (auto t = texture(m.occlusionTexture))
            out["occlusionTexture"] = {{"index", (*t)["index"]}, {"strength", m.occlusionStrength}};
        if (auto t = texture(m.emissiveTexture)) out["emissiveTexture"] = *t;
        // Emissive factors above 1 would need KHR_materials_emissive_strength: clamped.
        const glm::vec3 emissive = glm::clamp(m.emissiveFactor, 0.0f, 1.0f);
        if (emissive != glm::vec3(0.0f)) out["emissiveFactor"] = vec3Json(emissive);
        if (m.alphaMode == mesh::AlphaMode::Mask) out["alphaMode"] = "MASK", out["alphaCutoff"] = m.alphaCutoff;
        out["pbrMetallicRoughness"] = pbr;
        return out;
    }

    void finish(json& doc, BinaryBuilder& binary) const {
        if (textures_.empty()) return;
        json images = json::array();
        for (int image : imageOrder_)
            images.push_back({{"bufferView", binary.addView(images_[size_t(image)].bytes)},
                              {"mimeType", images_[size_t(image)].mimeType}});
        doc["images"] = images;
        doc["samplers"] = samplers_;
        doc["textures"] = textures_;
    }

private:
    std::optional<json> texture(const mesh::TextureRef& ref) {
        if (!ref.present() || size_t(ref.image) >= images_.size() || images_[size_t(ref.image)].bytes.empty())
            return std::nullopt;
        const auto [image, fresh] = imageIndex_.try_emplace(ref.image, int(imageIndex_.size()));
        if (fresh) imageOrder_.push_back(ref.image);
        const json sampler = {{"magFilter", ref.nearest ? kNearest : kLinear},
                              {"minFilter", kLinearMipmapLinear},
                              {"wrapS", wrapEnum(ref.wrapS)},
                              {"wrapT", wrapEnum(ref.wrapT)}};
        auto found = std::find(samplers_.begin(), samplers_.end(), sampler);
        const int samplerIndex = int(found - samplers_.begin());
        if (found == samplers_.end()) samplers_.push_back(sampler);
        const json texture = {{"source", image->second}, {"sampler", samplerIndex}};
        auto existing = std::find(textures_.begin(), textures_.end(), texture);
        const int index = int(existing - textures_.begin());
        if (existing == textures_.end()) textures_.push_back(texture);
        return json{{"index", index}};
    }

    const std::vector<EncodedImage>& images_;
    std::map<int, int> imageIndex_;  // image of the set -> image of the document
    std::vector<int> imageOrder_;    // images of the set, in the document's order
    json samplers_ = json::array(), textures_ = json::array();
};

std::vector<unsigned char> document(const mesh::PolygonMesh& triangles, const std::vector<glm::vec3>& normals,
                                    const std::vector<EncodedImage>& images, const std::optional<DracoBits>& draco) {
    SUBDFIT_CHECK(triangles.materials && triangles.faceMaterials.size() == size_t(triangles.faceCount()));
    SUBDFIT_CHECK(normals.empty() || normals.size() == triangles.positions.size());
    const bool hasNormals = !normals.empty();
    const mesh::MaterialSet& set = *triangles.materials;
    glm::ivec2 largest(1, 1);
    for (const auto& image : set.images) largest = glm::max(largest, glm::ivec2(image.width, image.height));
    BinaryBuilder binary;
    TexturedDocument textures(images);
    json primitives = json::array(), accessors = json::array(), materials = json::array();
    for (size_t m = 0; m < set.materials.size(); ++m) {
        const mesh::Material& material = set.materials[m];
        const GltfMesh part = primitiveOf(triangles, normals, int(m), material.baseColorTexture.uvTransform, largest);
        if (part.indices.empty()) continue;
        json primitive = {{"material", materials.size()}, {"mode", kTriangles}};
        materials.push_back(textures.material(material));
        const auto first = accessors.size();
        if (draco) {
            const DracoEncodedMesh encoded = encodeDraco(part, *draco);
            const int view = binary.addView(encoded.bytes);
            json ids = {{"POSITION", encoded.position}};
            accessors.push_back(accessor(-1, kFloat, encoded.vertexCount, "VEC3"));
            accessors.back()["min"] = vec3Json(encoded.positionMin);
            accessors.back()["max"] = vec3Json(encoded.positionMax);
            if (hasNormals) {
                ids["NORMAL"] = encoded.normal;
                accessors.push_back(accessor(-1, kFloat, encoded.vertexCount, "VEC3"));
            }
            if (part.hasUvs()) {
                ids["TEXCOORD_0"] = encoded.texcoord;
                accessors.push_back(accessor(-1, kFloat, encoded.vertexCount, "VEC2"));
            }
            primitive["attributes"] = attributesFrom(first, hasNormals, part.hasUvs());
            primitive["indices"] = accessors.size();
            accessors.push_back(accessor(-1, kUnsignedInt, encoded.triangleCount * 3, "SCALAR"));
            primitive["extensions"][kDraco] = {{"bufferView", view}, {"attributes", ids}};
        } else {
            glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
            for (const glm::vec3& p : part.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
            const size_t n = part.vertexCount();
            accessors.push_back(accessor(binary.addArray(part.positions, kArrayBuffer), kFloat, n, "VEC3"));
            accessors.back()["min"] = vec3Json(lo);
            accessors.back()["max"] = vec3Json(hi);
            if (hasNormals)
                accessors.push_back(accessor(binary.addArray(part.normals, kArrayBuffer), kFloat, n, "VEC3"));
            if (part.hasUvs())
                accessors.push_back(accessor(binary.addArray(part.uvs, kArrayBuffer), kFloat, n, "VEC2"));
            primitive["attributes"] = attributesFrom(first, hasNormals, part.hasUvs());
            primitive["indices"] = accessors.size();
            accessors.push_back(accessor(binary.addArray(part.indices, kElementArrayBuffer), kUnsignedInt,
                                         part.indices.size(), "SCALAR"));
        }
        primitives.push_back(primitive);
    }
    if (primitives.empty()) throw Error("nothing to export: the mesh has no triangles");
    json doc = {{"asset", {{"version", "2.0"}, {"generator", "subdfit"}}},
                {"scene", 0},
                {"scenes", json::array({{{"nodes", {0}}}})},
                {"nodes", json::array({{{"mesh", 0}}})},
                {"meshes", json::array({{{"primitives", primitives}}})},
                {"materials", materials},
                {"accessors", accessors}};
    textures.finish(doc, binary);
    if (draco) doc["extensionsUsed"] = doc["extensionsRequired"] = json::array({kDraco});
    doc["bufferViews"] = binary.views();
    doc["buffers"] = json::array({{{"byteLength", binary.data().size()}}});
    return packGlb(doc, binary.data());
}

}  // namespace

io::WrittenFile writeTexturedGlb(const std::filesystem::path& path, const mesh::PolygonMesh& triangles,
                                 const std::vector<glm::vec3>& normals, const std::vector<EncodedImage>& images,
                                 bool draco) {
    return writeTexturedGlb(path, triangles, normals, images,
                            draco ? std::optional<DracoBits>(DracoBits{}) : std::nullopt);
}

io::WrittenFile writeTexturedGlb(const std::filesystem::path& path, const mesh::PolygonMesh& triangles,
                                 const std::vector<glm::vec3>& normals, const std::vector<EncodedImage>& images,
                                 const std::optional<DracoBits>& draco) {
    std::vector<unsigned char> bytes;
    try {
        bytes = document(triangles, normals, images, draco);
    } catch (const Error& e) {
        throw fileError(path.string(), e.what());
    }
    return io::writeBytes(path, bytes);
}

}  // namespace subdfit::exporter
