#pragma once
// A GltfMesh as a Draco bitstream for glTF's KHR_draco_mesh_compression.
#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "export/gltf_mesh.h"

namespace subdfit::exporter {

struct DracoEncodedMesh {
    std::vector<unsigned char> bytes;
    // Draco unique ids of the attributes, as the extension's `attributes` names them; -1 when absent.
    int position = -1, normal = -1, tangent = -1, texcoord = -1;
    // Of the mesh as a decoder gets it back (the accessors must describe that, not our input).
    std::size_t vertexCount = 0, triangleCount = 0;
    glm::vec3 positionMin{0.0f}, positionMax{0.0f};
};

// Quantisation of positions and normals, bits per component.
struct DracoBits {
    int position = 14, normal = 10;
};

// Quantisation: positions and normals as `bits` says, tangent (a generic attribute) 10 bits,
// texcoord 12 or more -- enough that the texcoord error stays below 1/64 texel of
// tess.atlasSize, since half a texel would already sample the neighbouring tile. Speed 5.
// Throws subdfit::Error when Draco fails.
DracoEncodedMesh encodeDraco(const GltfMesh& tess, DracoBits bits = {});

}  // namespace subdfit::exporter
