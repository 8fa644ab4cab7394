// `subdfit-bench relief`: writes the dense reference README command 1 and the simplify
// benchmark run on (surface/relief_surface.h): no download, no license question.
#include <cstdio>

#include "bench_commands.h"
#include "export/glb_writer.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"

namespace subdfit::bench {

int writeReliefReference(const ReliefOptions& o) {
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
