#include "export/gltf/glb_writer.h"

#include <cstring>
#include <limits>

#include <glm/common.hpp>
#include <nlohmann/json.hpp>

#include "export/gltf/draco_encoding.h"
#include "export/gltf/glb_container.h"
#include "export/gltf/gltf_builder.h"
#include "export/gltf/meshopt_encoding.h"
#include "export/surface_mesh.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

using nlohmann::json;

using namespace gltf;

void checkTessellation(const GltfMesh& tess) {
    SUBDFIT_CHECK(tess.attributesConsistent());
    if (tess.vertexCount() == 0 || tess.indices.empty()) throw Error("nothing to export: the mesh has no triangles");
}

// The material, and the textures it names in `doc` (images in buffer views of `binary`).
json material(const FittedTextures& t, json& doc, BinaryBuilder& binary) {
    const SurfaceMaterial factors = surfaceMaterial({.baseColor = !t.baseColorPng.empty(),
                                                     .metallicRoughness = !t.metallicRoughnessPng.empty(),
                                                     .emissive = !t.emissivePng.empty()});
    json pbr = {{"baseColorFactor", factors.baseColorFactor},
                {"metallicFactor", factors.metallicFactor},
                {"roughnessFactor", factors.roughnessFactor}};
    json m = {{"name", "subdfit"}};
    auto texture = [&](const std::vector<unsigned char>& png, const char* name) {
        const int view = binary.addView(png);
        if (!doc.contains("images")) {
            doc["images"] = doc["textures"] = json::array();
            // No mipmaps: each atlas tile is its own chart, and a coarser level would mix tiles.
            doc["samplers"] = json::array(
                {{{"magFilter", kLinear}, {"minFilter", kLinear}, {"wrapS", kClampToEdge}, {"wrapT", kClampToEdge}}});
        }
        doc["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}, {"name", name}});
        doc["textures"].push_back({{"sampler", 0}, {"source", doc["images"].size() - 1}});
        return json{{"index", doc["textures"].size() - 1}};
    };
    if (!t.baseColorPng.empty()) {
        pbr["baseColorTexture"] = texture(t.baseColorPng, "base_color");
        if (!t.metallicRoughnessPng.empty()) {
            pbr["metallicRoughnessTexture"] = texture(t.metallicRoughnessPng, "metallic_roughness");
            if (t.occlusionInMetallicRoughness) m["occlusionTexture"] = pbr["metallicRoughnessTexture"];
        }
    }
    if (!t.normalPng.empty()) m["normalTexture"] = texture(t.normalPng, "normal");
    if (!t.emissivePng.empty()) {
        m["emissiveTexture"] = texture(t.emissivePng, "emissive");
        m["emissiveFactor"] = factors.emissiveFactor;
    }
    m["pbrMetallicRoughness"] = pbr;
    return m;
}

// The primitive's vertex attributes, in accessor order: what the mesh has.
struct AttributeSlot {
    const char* name;
    const char* type;
    int dracoId;
};

std::vector<AttributeSlot> presentAttributes(const GltfMesh& tess, const DracoEncodedMesh& ids) {
    std::vector<AttributeSlot> slots{{"POSITION", "VEC3", ids.position}};
    if (tess.hasNormals()) slots.push_back({"NORMAL", "VEC3", ids.normal});
    if (tess.hasTangents()) slots.push_back({"TANGENT", "VEC4", ids.tangent});
    if (tess.hasUvs()) slots.push_back({"TEXCOORD_0", "VEC2", ids.texcoord});
    return slots;
}

json document(const GltfMesh& tess, const FittedTextures& textures, MeshCoding coding, DracoBits dracoBits,
              const json& meshExtras, BinaryBuilder& binary) {
    const bool draco = coding == MeshCoding::Draco;
    const DracoEncodedMesh encoded = draco ? encodeDraco(tess, dracoBits) : DracoEncodedMesh{};
    const auto slots = presentAttributes(tess, encoded);
    json attributes = json::object(), dracoAttributes = json::object();
    json accessors = json::array();
    for (size_t i = 0; i < slots.size(); ++i) {
        attributes[slots[i].name] = i;
        dracoAttributes[slots[i].name] = slots[i].dracoId;
    }
    json primitive = {{"attributes", attributes}, {"indices", slots.size()}, {"mode", kTriangles}};
    // A material only where there is an appearance: a surface whose reference had none is drawn
    // as the reader draws a mesh without one, as it drew the reference.
    const bool hasMaterial = textures.any();
    if (hasMaterial) primitive["material"] = 0;
    json node = {{"mesh", 0}, {"name", "fitted"}};

    if (coding == MeshCoding::Meshopt || coding == MeshCoding::Quantized) {
        const MeshoptPrimitive packed = addQuantizedPrimitive(tess, binary, accessors, coding == MeshCoding::Meshopt);
        primitive["attributes"] = packed.attributes;
        primitive["indices"] = packed.indices;
        node["translation"] = packed.translation;
        node["scale"] = {packed.scale, packed.scale, packed.scale};
    } else if (draco) {
        const int view = binary.addView(encoded.bytes);
        for (const auto& slot : slots) accessors.push_back(accessor(-1, kFloat, encoded.vertexCount, slot.type));
        accessors[0]["min"] = vec3Json(encoded.positionMin);
        accessors[0]["max"] = vec3Json(encoded.positionMax);
        accessors.push_back(accessor(-1, kUnsignedInt, encoded.triangleCount * 3, "SCALAR"));
        primitive["extensions"][kDraco] = {{"bufferView", view}, {"attributes", dracoAttributes}};
    } else {
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
        for (const glm::vec3& p : tess.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
        const size_t n = tess.vertexCount();
        accessors.push_back(accessor(binary.addArray(tess.positions, kArrayBuffer), kFloat, n, "VEC3"));
        accessors.back()["min"] = vec3Json(lo);  // required for POSITION (spec 5.1.1)
        accessors.back()["max"] = vec3Json(hi);
        if (tess.hasNormals())
            accessors.push_back(accessor(binary.addArray(tess.normals, kArrayBuffer), kFloat, n, "VEC3"));
        if (tess.hasTangents())
            accessors.push_back(accessor(binary.addArray(tess.tangents, kArrayBuffer), kFloat, n, "VEC4"));
        if (tess.hasUvs()) accessors.push_back(accessor(binary.addArray(tess.uvs, kArrayBuffer), kFloat, n, "VEC2"));
        accessors.push_back(
            accessor(binary.addArray(tess.indices, kElementArrayBuffer), kUnsignedInt, tess.indices.size(), "SCALAR"));
    }

    json doc = {{"asset", {{"version", "2.0"}, {"generator", "subdfit"}}},
                {"scene", 0},
                {"scenes", json::array({{{"nodes", {0}}}})},
                {"nodes", json::array({node})},
                {"meshes", json::array({{{"name", "fitted"}, {"primitives", json::array({primitive})}}})},
                {"accessors", accessors}};
    if (!meshExtras.empty()) doc["meshes"][0]["extras"] = meshExtras;
    if (hasMaterial) doc["materials"] = json::array({material(textures, doc, binary)});
    if (draco) doc["extensionsUsed"] = doc["extensionsRequired"] = json::array({kDraco});
    if (coding == MeshCoding::Meshopt)
        doc["extensionsUsed"] = doc["extensionsRequired"] = json::array({kMeshopt, kQuantization});
    if (coding == MeshCoding::Quantized)
        doc["extensionsUsed"] = doc["extensionsRequired"] = json::array({kQuantization});
    doc["bufferViews"] = binary.views();
    doc["buffers"] = binary.buffers();
    return doc;
}

std::vector<unsigned char> encodeGlb(const GltfMesh& tess, const FittedTextures& textures, MeshCoding coding,
                                     DracoBits dracoBits, const json& meshExtras) {
    checkTessellation(tess);
    BinaryBuilder binary;
    const json doc = document(tess, textures, coding, dracoBits, meshExtras, binary);
    return packGlb(doc, binary.data());
}

io::WrittenFile writeGlb(const std::filesystem::path& path, const GltfMesh& tess, const FittedTextures& textures,
                         MeshCoding coding, const json& meshExtras, DracoBits dracoBits = {}) {
    std::vector<unsigned char> bytes;
    try {
        bytes = encodeGlb(tess, textures, coding, dracoBits, meshExtras);
    } catch (const Error& e) {
        throw fileError(path.string(), e.what());
    }
    return io::writeBytes(path, bytes);
}

MeshCoding codingOf(bool draco) { return draco ? MeshCoding::Draco : MeshCoding::Float; }

}  // namespace

io::WrittenFile writeFittedGlb(const std::filesystem::path& path, const GltfMesh& tess,
                               std::span<const unsigned char> normalPng, bool draco) {
    return writeGlb(path, tess, {.normalPng = {normalPng.begin(), normalPng.end()}}, codingOf(draco), json::object());
}

io::WrittenFile writeFittedGlb(const std::filesystem::path& path, const GltfMesh& tess, const FittedTextures& textures,
                               bool draco) {
    return writeGlb(path, tess, textures, codingOf(draco), json::object());
}

std::vector<unsigned char> encodeFittedGlb(const GltfMesh& tess, const FittedTextures& textures, MeshCoding coding) {
    return encodeGlb(tess, textures, coding, DracoBits{}, json::object());
}

io::WrittenFile writeFittedGlb(const std::filesystem::path& path, const GltfMesh& tess, const FittedTextures& textures,
                               MeshCoding coding) {
    return writeGlb(path, tess, textures, coding, json::object());
}

io::WrittenFile writeMeshGlb(const std::filesystem::path& path, const std::vector<glm::vec3>& positions,
                             const std::vector<glm::vec3>& normals, const std::vector<std::uint32_t>& indices,
                             bool draco, const nlohmann::json& extras) {
    return writeMeshGlb(path, positions, normals, indices, draco ? std::optional<DracoBits>(DracoBits{}) : std::nullopt,
                        extras);
}

io::WrittenFile writeMeshGlb(const std::filesystem::path& path, const std::vector<glm::vec3>& positions,
                             const std::vector<glm::vec3>& normals, const std::vector<std::uint32_t>& indices,
                             const std::optional<DracoBits>& draco, const nlohmann::json& extras) {
    GltfMesh mesh;
    mesh.positions = positions;
    mesh.normals = normals;
    mesh.indices = indices;
    return writeGlb(path, mesh, FittedTextures{}, codingOf(draco.has_value()), extras, draco.value_or(DracoBits{}));
}

}  // namespace subdfit::exporter
