#pragma once
// The fitted asset as one self-contained .glb: the displaced limit tessellation with normals,
// tangents and atlas texcoords, and a plain grey material whose normalTexture is the fitted
// normal atlas -- viewable in any glTF viewer.
#include <filesystem>
#include <optional>
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

#include "export/gltf/draco_encoding.h"
#include "export/gltf_mesh.h"
#include "io/output_file.h"

namespace subdfit::exporter {

// One scene, node, mesh and primitive (POSITION, and NORMAL, TANGENT, TEXCOORD_0 where the
// tessellation has them, uint32 indices); with texcoords or a normal map, one material
// (metallic 0, roughness 0.6; normalTexture = the embedded `normalPng` unless it is empty,
// sampled LINEAR without mipmaps and clamped, as the atlas requires). With `draco`,
// the primitive is KHR_draco_mesh_compression-encoded (export/gltf/draco_encoding.h) and the
// extension is required. Written atomically; throws subdfit::Error "path: problem".
io::WrittenFile writeFittedGlb(const std::filesystem::path& path, const GltfMesh& tess,
                               std::span<const unsigned char> normalPng, bool draco);

// The material's images (PNG bytes, all on the texcoords of `tess`; empty: none). With a base
// colour the material is the fitted one: baseColorTexture (factor 1), and with a
// metallic-roughness image its metallicRoughnessTexture (factors 1), else metallic 0, roughness 1.
struct FittedTextures {
    std::vector<unsigned char> normalPng{}, baseColorPng{}, metallicRoughnessPng{}, emissivePng{};
    bool occlusionInMetallicRoughness = false;  // its red channel is the occlusionTexture
    bool any() const {
        return !normalPng.empty() || !baseColorPng.empty() || !metallicRoughnessPng.empty() || !emissivePng.empty();
    }
};
io::WrittenFile writeFittedGlb(const std::filesystem::path& path, const GltfMesh& tess, const FittedTextures& textures,
                               bool draco);

// How a writer stores the mesh: float accessors as they are; KHR_draco_mesh_compression
// (export/gltf/draco_encoding.h); KHR_mesh_quantization alone, which every glTF reader opens with no
// decoder set; or with EXT_meshopt_compression besides (export/gltf/meshopt_encoding.h), what engines
// with meshoptimizer's decoder load smallest. The extensions a coding uses are required.
enum class MeshCoding { Float, Draco, Quantized, Meshopt };

// The .glb of writeFittedGlb, in memory, with the mesh stored as `coding` says.
std::vector<unsigned char> encodeFittedGlb(const GltfMesh& tess, const FittedTextures& textures, MeshCoding coding);
io::WrittenFile writeFittedGlb(const std::filesystem::path& path, const GltfMesh& tess, const FittedTextures& textures,
                               MeshCoding coding);

// A plain triangle mesh (a cage, a decimated mesh): positions, optional normals, indices;
// `extras` (if not empty) goes into the mesh's glTF `extras`.
io::WrittenFile writeMeshGlb(const std::filesystem::path& path, const std::vector<glm::vec3>& positions,
                             const std::vector<glm::vec3>& normals, const std::vector<std::uint32_t>& indices,
                             bool draco, const nlohmann::json& extras = nlohmann::json::object());
// The same, Draco-coded at `draco`'s quantisation when given.
io::WrittenFile writeMeshGlb(const std::filesystem::path& path, const std::vector<glm::vec3>& positions,
                             const std::vector<glm::vec3>& normals, const std::vector<std::uint32_t>& indices,
                             const std::optional<DracoBits>& draco,
                             const nlohmann::json& extras = nlohmann::json::object());

}  // namespace subdfit::exporter
