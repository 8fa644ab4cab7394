#pragma once
// What a glTF's JSON goes through before tinygltf 2.7 (Debian 12) sees it, in one parse:
//  - refusals of what tinygltf would take silently: a negative byteOffset, byteLength,
//    byteStride or count (it reads them as 0), and an external URI that is absolute, has a
//    scheme, or leaves the file's folder once percent-decoded and normalised;
//  - a workaround: tinygltf refuses any primitive whose `indices` accessor has no bufferView,
//    which is exactly how KHR_draco_mesh_compression primitives are written (their indices live
//    in the Draco payload, and we never read those accessors), so that member is removed.
#include <string>

namespace subdfit::mesh::gltf {

// Checks and rewrites a .gltf text or a .glb container in place. Throws subdfit::Error naming
// `path` for a refused field or URI; leaves malformed bytes for tinygltf to report.
void preflight(std::string& bytes, const std::string& path);

// Why an external (non-data:) URI may not be followed, "" when it may: the reason names it.
std::string uriProblem(const std::string& uri);

}  // namespace subdfit::mesh::gltf
