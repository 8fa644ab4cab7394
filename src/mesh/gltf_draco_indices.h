#pragma once
// A workaround for tinygltf 2.7 (Debian 12), which refuses any primitive whose `indices`
// accessor has no bufferView ("accessor[0] invalid bufferView"). That is exactly how
// KHR_draco_mesh_compression primitives are written: their indices live in the Draco payload.
// We never read those accessors, so the `indices` member of every Draco primitive is removed
// from the JSON before tinygltf sees it.
#include <string>

namespace subdfit::mesh::gltf {

// Rewrites a .gltf text or a .glb container in place. Leaves bytes untouched when nothing
// needs it or when they are malformed (tinygltf then reports the problem).
void dropDracoPrimitiveIndices(std::string& bytes);

}  // namespace subdfit::mesh::gltf
