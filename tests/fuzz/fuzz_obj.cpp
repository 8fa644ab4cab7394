// OBJ with OpenSubdiv tags through the full loader (validation included): any input must give a
// mesh or subdfit::Error, never a crash, a sanitizer report or another exception type.
#include "fuzz_input_file.h"
#include "mesh/mesh_loader.h"
#include "util/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const auto path = writeFuzzInput(data, size, ".obj");
    try {
        const auto mesh = subdfit::mesh::loadMesh(path);
        (void)subdfit::mesh::vertexNormals(subdfit::mesh::triangulated(mesh));
    } catch (const subdfit::Error&) {
    }
    return 0;
}
