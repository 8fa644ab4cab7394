// `subdfit-bench relief`: writes the dense reference README command 1 and the simplify
// benchmark run on (surface/relief_surface.h): no download, no license question.
#include <cstdio>

#include "bench_commands.h"
#include "export/glb_writer.h"
#include "mesh/mesh_geometry.h"
#include "mesh/mesh_loader.h"

namespace subdfit::bench {

int runRelief(const ReliefOptions& o) {
    const mesh::PolygonMesh surface = surface::reliefSurface(mesh::loadMesh(o.cage), o.relief);
    std::filesystem::create_directories(std::filesystem::absolute(o.out).parent_path());
    const auto written = exporter::writeMeshGlb(o.out, surface.positions, mesh::vertexNormals(surface),
                                                {surface.faceIndices.begin(), surface.faceIndices.end()}, /*draco=*/false);
    std::printf("%s: %d triangles, %ju bytes\n", written.path.string().c_str(), surface.faceCount(), written.bytes);
    return 0;
}

}  // namespace subdfit::bench
