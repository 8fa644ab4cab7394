#include "export/gltf_mesh.h"

namespace subdfit::exporter {

GltfMesh gltfMesh(const surface::Tessellation& t, const codec::AtlasLayout& atlas) {
    return gltfMesh(surface::Tessellation(t), atlas);
}

GltfMesh gltfMesh(surface::Tessellation&& t, const codec::AtlasLayout& atlas) {
    GltfMesh mesh;
    mesh.atlasSize = {atlas.width, atlas.height};
    mesh.uvs.reserve(t.ptex.size());
    for (const surface::PtexPoint& p : t.ptex) mesh.uvs.push_back(codec::atlasUv(atlas, p.face, p.u, p.v));
    mesh.positions = std::move(t.positions);
    mesh.normals = std::move(t.normals);
    mesh.tangents = std::move(t.tangents);
    mesh.indices = std::move(t.indices);
    return mesh;
}

}  // namespace subdfit::exporter
