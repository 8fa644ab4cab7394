// One mesh loader under libFuzzer (as a cage and as a reference), the format chosen at build time (SUBDFIT_FUZZ_EXTENSION:
// ".obj" for OBJ with OpenSubdiv tags, ".glb" for glTF with embedded buffers and Draco). Any
// input must give a mesh or subdfit::Error: never a crash, a sanitizer report or another
// exception type. The loaders read paths (they name the file in every error), so each input
// goes through a file in memory-backed /dev/shm.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "mesh/mesh_loader.h"
#include "util/error.h"
#include "util/warnings.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const std::string path = "/dev/shm/subdfit_fuzz_" + std::to_string(getpid()) + SUBDFIT_FUZZ_EXTENSION;
    static const auto quiet = subdfit::setWarningSink([](const std::string&) {});  // warnings are not failures
    (void)quiet;
    if (FILE* f = std::fopen(path.c_str(), "wb")) {
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    try {
        const auto mesh = subdfit::mesh::loadMesh(path);
        (void)subdfit::mesh::vertexNormals(subdfit::mesh::triangulated(mesh));
    } catch (const subdfit::Error&) {}
    // As a reference: texture coordinates, colours, materials and embedded images too.
    try {
        const auto mesh = subdfit::mesh::loadReference(path);
        (void)subdfit::mesh::vertexNormals(subdfit::mesh::triangulated(mesh));
    } catch (const subdfit::Error&) {}
    return 0;
}
