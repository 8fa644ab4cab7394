#include "mesh/mesh_validation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

#include "util/error.h"
#include "util/warnings.h"

namespace subdfit::mesh {

namespace {

bool inRange(int index, int count) { return index >= 0 && index < count; }

// OpenSubdiv drops a crease whose two vertices share no edge with only a warning of its own;
// an artist who tagged it meant something, so say which.
void warnAboutCreasesOffEdges(const PolygonMesh& mesh) {
    if (mesh.tags.creases.empty()) return;
    std::unordered_set<std::uint64_t> edges;
    auto key = [](int a, int b) {
        return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
    };
    size_t corner = 0;
    for (int size : mesh.faceSizes) {
        for (int k = 0; k < size; ++k)
            edges.insert(key(mesh.faceIndices[corner + size_t(k)], mesh.faceIndices[corner + size_t((k + 1) % size)]));
        corner += size_t(size);
    }
    int offEdges = 0;
    const Crease* first = nullptr;
    for (const Crease& c : mesh.tags.creases)
        if (!edges.count(key(c.v0, c.v1))) {
            ++offEdges;
            if (!first) first = &c;
        }
    if (first)
        warn(mesh.sourcePath + ": " + std::to_string(offEdges) + " crease tag" + (offEdges > 1 ? "s join" : " joins") +
             " vertices that share no edge (first: " + std::to_string(first->v0) + "-" + std::to_string(first->v1) +
             "); OpenSubdiv ignores " + (offEdges > 1 ? "them" : "it"));
}

void validateTags(const PolygonMesh& mesh) {
    const std::string& path = mesh.sourcePath;
    const int vertices = mesh.vertexCount();
    for (const Crease& c : mesh.tags.creases)
        if (!inRange(c.v0, vertices) || !inRange(c.v1, vertices) || !(c.sharpness >= 0.0f))
            throw fileError(path, "crease " + std::to_string(c.v0) + "-" + std::to_string(c.v1) +
                                      " names a missing vertex or has a bad sharpness");
    for (const Corner& c : mesh.tags.corners)
        if (!inRange(c.vertex, vertices) || !(c.sharpness >= 0.0f))
            throw fileError(path,
                            "corner " + std::to_string(c.vertex) + " names a missing vertex or has a bad sharpness");
    for (int f : mesh.tags.holes)
        if (!inRange(f, mesh.faceCount())) throw fileError(path, "hole tag names missing face " + std::to_string(f));
    warnAboutCreasesOffEdges(mesh);
}

// The readers build these consistently; this is the contract for every other producer.
void validateAppearance(const PolygonMesh& mesh) {
    const std::string& path = mesh.sourcePath;
    const size_t vertices = mesh.positions.size();
    if ((!mesh.uvs.empty() && mesh.uvs.size() != vertices) || (!mesh.colors.empty() && mesh.colors.size() != vertices))
        throw fileError(path, "texture coordinates or colours do not match the vertices");
    if (!mesh.normals.empty() && mesh.normals.size() != vertices)
        throw fileError(path, "normals do not match the vertices");
    if (!mesh.materials) {
        if (!mesh.faceMaterials.empty()) throw fileError(path, "faces name materials, but there are none");
        return;
    }
    if (mesh.faceMaterials.size() != mesh.faceSizes.size()) throw fileError(path, "not every face has a material");
    for (int m : mesh.faceMaterials)
        if (!inRange(m, int(mesh.materials->materials.size())))
            throw fileError(path, "a face names material " + std::to_string(m) + ", which does not exist");
    const int images = int(mesh.materials->images.size());
    for (const Material& m : mesh.materials->materials)
        for (const TextureRef* t : {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture,
                                    &m.occlusionTexture, &m.emissiveTexture})
            if (t->present() && !inRange(t->image, images))
                throw fileError(path, "material '" + m.name + "' names image " + std::to_string(t->image) +
                                          ", which does not exist");
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
    validateAppearance(mesh);
}

}  // namespace subdfit::mesh
