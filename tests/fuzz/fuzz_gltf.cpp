// GLB (glTF with embedded buffers, KHR_draco_mesh_compression included) through the full
// loader: any input must give a mesh or subdfit::Error, never a crash or a sanitizer report.
#include "fuzz_input_file.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto path = writeFuzzInput(data, size, ".glb");
    try {
        const auto mesh = subdfit::mesh::loadMesh(path);
        (void)subdfit::mesh::vertexNormals(subdfit::mesh::triangulated(mesh));
    } catch (const subdfit::Error&) {
    }
    return 0;
}
