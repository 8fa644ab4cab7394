#pragma once
// EXT_meshopt_compression (what `gltfpack -c` writes), undone before tinygltf 2.7 sees the
// file, which knows nothing of it: every compressed bufferView is decoded by meshoptimizer
// (vertex and index codecs, octahedral / quaternion / exponential filters) into the GLB's
// binary chunk, the fallback buffers are dropped and the extension is no longer required.
#include <string>

namespace subdfit::mesh::gltf {

// Rewrites a .glb container in place when its JSON uses the extension; anything else is left as
// it is. Throws subdfit::Error naming `path` for compressed data that does not decode or lies
// outside the binary chunk (a .gltf text with compressed buffers is refused the same way).
void expandMeshopt(std::string& bytes, const std::string& path);

}  // namespace subdfit::mesh::gltf
