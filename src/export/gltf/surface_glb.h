#pragma once
// The displaced limit surface of a cage and its maps as one .glb: what `fit` writes as its
// fitted.glb preview and what `subdfit decode` writes from a shipped asset.subd.
#include <filesystem>

#include "export/gltf/glb_writer.h"
#include "io/output_file.h"
#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::exporter {

// What the .glb holds: the tessellation (`segments` per ptex-face edge; texcoords on the maps'
// atlas where an image reads them, tangents where a normal texture does) and the material's
// images (the normal map, if any, as the normalTexture), each PNG-encoded; no image, no material.
struct SurfaceGlb {
    GltfMesh mesh;
    FittedTextures textures;
};
SurfaceGlb surfaceGlb(const mesh::PolygonMesh& cage, const surface::SurfaceMaps& maps, int segments);

// `mesh` without what no image of `textures` reads: tangents without a normal texture, texture
// coordinates without any image (surfaceGlb's mesh is so already; a level of detail made apart).
void withoutUnreadAttributes(GltfMesh& mesh, const FittedTextures& textures);

io::WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                                const surface::SurfaceMaps& maps, int segments, MeshCoding coding);
inline io::WrittenFile writeSurfaceGlb(const std::filesystem::path& path, const mesh::PolygonMesh& cage,
                                       const surface::SurfaceMaps& maps, int segments, bool draco) {
    return writeSurfaceGlb(path, cage, maps, segments, draco ? MeshCoding::Draco : MeshCoding::Float);
}

}  // namespace subdfit::exporter
