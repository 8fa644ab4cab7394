#pragma once
// A triangle mesh with its materials as one self-contained .glb, one primitive per material:
// what the triangle baselines ship when the reference has an appearance (decimation keeps the
// texture coordinates, the images are re-encoded at the scale the budget allows).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "export/gltf/draco_encoding.h"
#include "io/output_file.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::exporter {

struct EncodedImage {
    std::vector<unsigned char> bytes;  // empty: the image is left out (and its textures)
    std::string mimeType;              // "image/png", "image/jpeg"
};

// `triangles` (triangulated, with faceMaterials and materials, uvs if it has any; in the units to write),
// `normals` per vertex (none: the file has none), `images[i]` the encoding of materials->images[i]. Each material's
// KHR_texture_transform is applied to its primitive's texture coordinates (that of its base
// colour texture; a material whose textures disagree keeps the base colour's). With `draco`
// every primitive is KHR_draco_mesh_compression-coded. Throws subdfit::Error "path: problem".
io::WrittenFile writeTexturedGlb(const std::filesystem::path& path, const mesh::PolygonMesh& triangles,
                                 const std::vector<glm::vec3>& normals, const std::vector<EncodedImage>& images,
                                 bool draco);
// The same, Draco-coded at `draco`'s quantisation when given.
io::WrittenFile writeTexturedGlb(const std::filesystem::path& path, const mesh::PolygonMesh& triangles,
                                 const std::vector<glm::vec3>& normals, const std::vector<EncodedImage>& images,
                                 const std::optional<DracoBits>& draco);

}  // namespace subdfit::exporter
