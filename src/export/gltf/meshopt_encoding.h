#pragma once
// A GltfMesh as engines load it compact, the way gltfpack ships meshes: KHR_mesh_quantization
// (positions as 14-bit integers on one grid over the mesh's bounding cube, dequantised by the
// node's translation and uniform scale, which leaves normals alone; normals and tangents as
// normalised bytes in the octahedral filter; texture coordinates as normalised 16-bit integers
// where they lie in [0, 1], floats elsewhere; indices of 16 bits where the vertices allow) and,
// optionally, EXT_meshopt_compression of every stream, after vertices equal in every quantised attribute are
// merged and meshoptimizer has ordered the triangles for the vertex cache and the vertices for
// fetching.
#include <array>

#include <nlohmann/json.hpp>

#include "export/gltf/gltf_builder.h"
#include "export/gltf_mesh.h"

namespace subdfit::exporter {

inline constexpr int kQuantisedPositionBits = 14;

// What the primitive and its node need: the accessors' indices and the node's dequantisation.
struct MeshoptPrimitive {
    nlohmann::json attributes = nlohmann::json::object();  // glTF attribute name -> accessor
    int indices = -1;
    std::array<double, 3> translation{0.0, 0.0, 0.0};
    double scale = 1.0;
};

// Appends the mesh's views to `binary` and its accessors to `accessors`: compressed with
// EXT_meshopt_compression, or (`compressed` false) plain, KHR_mesh_quantization alone, which every
// glTF reader opens without a decoder (normals and tangents then as x, y, z normalised bytes).
MeshoptPrimitive addQuantizedPrimitive(const GltfMesh& mesh, gltf::BinaryBuilder& binary, nlohmann::json& accessors,
                                       bool compressed);

}  // namespace subdfit::exporter
