// `subdfit-bench relief`: writes the dense reference README command 1 and the simplify
// benchmark run on (surface/relief_surface.h): no download, no license question. With --mesh, a
// dense textured one instead: a light asset's triangles split (mesh/triangle_subdivision.h) and
// the same relief added, its materials and images kept.
#include <cstdio>

#include "bench_commands.h"
#include "export/gltf/glb_writer.h"
#include "export/gltf/textured_glb.h"
#include "io/image_io.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"
#include "mesh/triangle_subdivision.h"

namespace subdfit::bench {

namespace {

// Its images as PNG, lossless: a reference loses nothing to its own encoding.
std::vector<exporter::EncodedImage> losslessImages(const mesh::MaterialSet& set) {
    std::vector<exporter::EncodedImage> out;
    for (const mesh::Image& image : set.images)
        out.push_back(
            {io::encodeImage({image.width, image.height, image.rgba}, image.width, image.height, io::ImageFormat::Png),
             "image/png"});
    return out;
}

int writeTexturedRelief(const ReliefOptions& o) {
    mesh::PolygonMesh surface = mesh::subdividedTriangles(mesh::triangulated(mesh::loadReference(o.mesh)), o.splits);
    surface::addRelief(surface, o.relief);
    std::filesystem::create_directories(std::filesystem::absolute(o.out).parent_path());
    const auto images = surface.materials ? losslessImages(*surface.materials) : std::vector<exporter::EncodedImage>{};
    if (!surface.materials)
        surface.materials = std::make_shared<mesh::MaterialSet>(mesh::MaterialSet{{mesh::defaultMaterial()}, {}});
    if (surface.faceMaterials.empty()) surface.faceMaterials.assign(size_t(surface.faceCount()), 0);
    exporter::writeTexturedGlb(o.out, surface, surface.normals, images, /*draco=*/false);
    return surface.faceCount();
}

}  // namespace

int writeReliefReference(const ReliefOptions& o) {
    if (!o.mesh.empty()) return writeTexturedRelief(o);
    const mesh::PolygonMesh surface = surface::reliefSurface(mesh::loadMesh(o.cage), o.relief);
    std::filesystem::create_directories(std::filesystem::absolute(o.out).parent_path());
    exporter::writeMeshGlb(o.out, surface.positions, mesh::vertexNormals(surface),
                           {surface.faceIndices.begin(), surface.faceIndices.end()}, /*draco=*/false);
    return surface.faceCount();
}

int runRelief(const ReliefOptions& o) {
    const int triangles = writeReliefReference(o);
    std::printf("%s: %d triangles, %ju bytes\n", o.out.string().c_str(), triangles, std::filesystem::file_size(o.out));
    return 0;
}

}  // namespace subdfit::bench
