#include "export/gltf_mesh.h"

namespace subdfit::exporter {

GltfMesh gltfMesh(const surface::Tessellation& t, const AtlasLayout& atlas) {
    GltfMesh mesh;
    mesh.positions = t.positions;
    mesh.normals = t.normals;
    mesh.tangents = t.tangents;
    mesh.indices = t.indices;
    mesh.atlasSize = {atlas.width, atlas.height};
    mesh.uvs.reserve(t.ptex.size());
    for (const surface::PtexPoint& p : t.ptex) mesh.uvs.push_back(atlasUv(atlas, p.face, p.u, p.v));
    return mesh;
}

}  // namespace subdfit::exporter
