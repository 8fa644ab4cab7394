#pragma once
// Bounds-checked reads of glTF accessors and buffer views. tinygltf parses the JSON and loads
// the buffers but checks none of the offsets, strides or counts against them; everything here
// is checked before a byte is read, so a hostile file yields an error, not a crash.
#include <tiny_gltf.h>

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace subdfit::mesh::gltf {

// Positions of a VEC3 accessor: float, or (KHR_mesh_quantization) 8/16-bit integers,
// normalized or not. NaN and Inf are errors.
std::vector<glm::vec3> readPositions(const tinygltf::Model& model, int accessor, const std::string& path);
// NORMAL, the same way (not yet normalised: a zero normal is the caller's to replace).
std::vector<glm::vec3> readNormals(const tinygltf::Model& model, int accessor, const std::string& path);

// TEXCOORD_n of a VEC2 accessor, and COLOR_n of a VEC3 (alpha 1) or VEC4 accessor: float, or
// normalized unsigned byte / short. NaN and Inf are errors.
std::vector<glm::vec2> readTexCoords(const tinygltf::Model& model, int accessor, const std::string& path);
std::vector<glm::vec4> readColors(const tinygltf::Model& model, int accessor, const std::string& path);

// Indices of a SCALAR unsigned byte/short/int accessor (not yet checked against a vertex count).
std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor, const std::string& path);

// The bytes of a buffer view (e.g. a Draco payload).
std::string_view bufferViewBytes(const tinygltf::Model& model, int bufferView, const std::string& path);

}  // namespace subdfit::mesh::gltf
