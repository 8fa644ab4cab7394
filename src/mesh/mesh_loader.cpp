#include "mesh/mesh_loader.h"

#include <algorithm>
#include <cctype>
#include <new>
#include <string>

#include "mesh/draco_reader.h"
#include "mesh/gltf_reader.h"
#include "mesh/obj_reader.h"
#include "util/error.h"

namespace subdfit::mesh {

namespace {

PolygonMesh readByExtension(const std::filesystem::path& path, MeshContent content) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".obj") return readObj(path, content);
    if (ext == ".gltf" || ext == ".glb") return readGltf(path, content);
    if (ext == ".drc") return readDraco(path);
    throw fileError(path.string(),
                    (ext.empty() ? std::string("no file extension") : "unsupported mesh format '" + ext + "'") +
                        " (expected .obj, .gltf, .glb or .drc)");
}

PolygonMesh load(const std::filesystem::path& path, MeshContent content) {
    try {
        PolygonMesh mesh = readByExtension(path, content);
        validateMesh(mesh);
        return mesh;
    } catch (const std::bad_alloc&) {
        // The limits (input_limits.h) keep a file's demands bounded; what remains is a machine
        // without the memory for a file within them.
        throw fileError(path.string(), "out of memory while reading it");
    }
}

}  // namespace

PolygonMesh loadMesh(const std::filesystem::path& path) { return load(path, MeshContent::Geometry); }

PolygonMesh loadReference(const std::filesystem::path& path) { return load(path, MeshContent::WithAppearance); }

}  // namespace subdfit::mesh
