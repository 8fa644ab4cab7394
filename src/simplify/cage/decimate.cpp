#include "simplify/cage/decimate.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <array>
#include <set>

#include "mesh/mesh_geometry.h"
#include "util/error.h"

namespace subdfit::simplify {
namespace {

// Keeps the non-degenerate, distinct triangles of `indices` and the vertices they use.
mesh::PolygonMesh compacted(const std::vector<glm::vec3>& positions, const std::vector<unsigned>& indices,
                            const std::string& sourcePath) {
    std::vector<unsigned> kept;
    std::set<std::array<unsigned, 3>> seen;  // a triangle twice (either winding) is non-manifold
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const unsigned a = indices[t], b = indices[t + 1], c = indices[t + 2];
        if (a == b || b == c || a == c) continue;
        std::array<unsigned, 3> key{a, b, c};
        std::sort(key.begin(), key.end());
        if (!seen.insert(key).second) continue;
        kept.insert(kept.end(), {a, b, c});
    }
    std::vector<unsigned> remap(positions.size());
    const size_t used = meshopt_optimizeVertexFetchRemap(remap.data(), kept.data(), kept.size(), positions.size());
    mesh::PolygonMesh out;
    out.sourcePath = sourcePath;
    out.positions.resize(used);
    for (size_t v = 0; v < positions.size(); ++v)
        if (remap[v] != ~0u) out.positions[remap[v]] = positions[v];
    out.faceSizes.assign(kept.size() / 3, 3);
    out.faceIndices.reserve(kept.size());
    for (unsigned i : kept) out.faceIndices.push_back(int(remap[i]));
    return out;
}

}  // namespace

mesh::PolygonMesh weldedTriangles(const mesh::PolygonMesh& input) {
    const mesh::PolygonMesh triangles = mesh::triangulated(input);
    const std::vector<unsigned> indices(triangles.faceIndices.begin(), triangles.faceIndices.end());
    std::vector<unsigned> remap(triangles.positions.size());
    const size_t unique =
        meshopt_generateVertexRemap(remap.data(), indices.data(), indices.size(), triangles.positions.data(),
                                    triangles.positions.size(), sizeof(glm::vec3));
    std::vector<glm::vec3> positions(unique);
    for (size_t v = 0; v < remap.size(); ++v)
        if (remap[v] != ~0u) positions[remap[v]] = triangles.positions[v];
    std::vector<unsigned> welded(indices.size());
    for (size_t i = 0; i < indices.size(); ++i) welded[i] = remap[indices[i]];
    return compacted(positions, welded, input.sourcePath);
}

namespace {

// meshoptimizer's sloppy simplifier on `indices`, to at most `target` indices.
std::vector<unsigned> sloppy(const mesh::PolygonMesh& triangles, const std::vector<unsigned>& indices, size_t target) {
    std::vector<unsigned> out(indices.size());
    out.resize(meshopt_simplifySloppy(out.data(), indices.data(), indices.size(), &triangles.positions[0].x,
                                      triangles.positions.size(), sizeof(glm::vec3), target, 1.0f));
    return out;
}

// What a reduction to `targetTriangles` left, compacted; throws where it left nothing.
mesh::PolygonMesh reduced(const mesh::PolygonMesh& triangles, const std::vector<unsigned>& kept, int targetTriangles) {
    if (kept.empty())
        throw fileError(triangles.sourcePath,
                        "decimation to " + std::to_string(targetTriangles) + " triangles left nothing");
    return compacted(triangles.positions, kept, triangles.sourcePath);
}

}  // namespace

mesh::PolygonMesh decimate(const mesh::PolygonMesh& triangles, int targetTriangles) {
    if (targetTriangles < 1) throw Error("cannot decimate to " + std::to_string(targetTriangles) + " triangles");
    const std::vector<unsigned> indices(triangles.faceIndices.begin(), triangles.faceIndices.end());
    const size_t target = size_t(targetTriangles) * 3;
    if (indices.size() <= target) return compacted(triangles.positions, indices, triangles.sourcePath);

    std::vector<unsigned> out(indices.size());
    // Any error is allowed (a relative 1 is the whole mesh): the face budget is what binds.
    out.resize(meshopt_simplify(out.data(), indices.data(), indices.size(), &triangles.positions[0].x,
                                triangles.positions.size(), sizeof(glm::vec3), target, 1.0f));
    if (out.size() > target * 2 || out.empty()) out = sloppy(triangles, indices, target);
    return reduced(triangles, out, targetTriangles);
}

mesh::PolygonMesh cluster(const mesh::PolygonMesh& triangles, int targetTriangles) {
    if (targetTriangles < 1) throw Error("cannot cluster to " + std::to_string(targetTriangles) + " triangles");
    const std::vector<unsigned> indices(triangles.faceIndices.begin(), triangles.faceIndices.end());
    const size_t target = size_t(targetTriangles) * 3;
    if (indices.size() <= target) return compacted(triangles.positions, indices, triangles.sourcePath);
    return reduced(triangles, sloppy(triangles, indices, target), targetTriangles);
}

}  // namespace subdfit::simplify
