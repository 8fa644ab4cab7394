#include "mesh/mesh_validation.h"

#include <cmath>
#include <cstdint>

#include "util/error.h"

namespace subdfit::mesh {

namespace {

bool inRange(int index, int count) { return index >= 0 && index < count; }

void validateTags(const PolygonMesh& mesh) {
    const std::string& path = mesh.sourcePath;
    const int vertices = mesh.vertexCount();
    for (const Crease& c : mesh.tags.creases)
        if (!inRange(c.v0, vertices) || !inRange(c.v1, vertices) || !(c.sharpness >= 0.0f))
            throw fileError(path, "crease " + std::to_string(c.v0) + "-" + std::to_string(c.v1) +
                                      " names a missing vertex or has a bad sharpness");
    for (const Corner& c : mesh.tags.corners)
        if (!inRange(c.vertex, vertices) || !(c.sharpness >= 0.0f))
            throw fileError(path, "corner " + std::to_string(c.vertex) +
                                      " names a missing vertex or has a bad sharpness");
    for (int f : mesh.tags.holes)
        if (!inRange(f, mesh.faceCount()))
            throw fileError(path, "hole tag names missing face " + std::to_string(f));
}

}  // namespace

void validateMesh(const PolygonMesh& mesh) {
    const std::string& path = mesh.sourcePath;
    if (mesh.faceSizes.empty()) throw fileError(path, "no faces (empty mesh)");
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const glm::vec3& p = mesh.positions[v];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            throw fileError(path, "vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
    int64_t total = 0;
    for (size_t f = 0; f < mesh.faceSizes.size(); ++f) {
        if (mesh.faceSizes[f] < 3)
            throw fileError(path, "face " + std::to_string(f) + " has " + std::to_string(mesh.faceSizes[f]) +
                                      " vertices (needs at least 3)");
        total += mesh.faceSizes[f];
    }
    if (total != int64_t(mesh.faceIndices.size()))
        throw fileError(path, "face sizes add up to " + std::to_string(total) + " but there are " +
                                  std::to_string(mesh.faceIndices.size()) + " face indices");
    for (int index : mesh.faceIndices)
        if (!inRange(index, mesh.vertexCount()))
            throw fileError(path, "face index " + std::to_string(index) + " is out of range (" +
                                      std::to_string(mesh.vertexCount()) + " vertices)");
    validateTags(mesh);
}

}  // namespace subdfit::mesh
