#include "export/engine/lod_chain.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <limits>
#include <map>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "codec/decode_density.h"
#include "export/engine/surface_error.h"
#include "export/surface_mesh.h"
#include "geometry/surface_distance.h"
#include "geometry/surface_queries.h"
#include "mesh/point_welder.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

// Level 0 as meshoptimizer simplifies it, made once for every level: its vertices merged where
// the material cannot tell them apart (coincident points with the same texture coordinates;
// without images, every coincident point), so that meshoptimizer sees one surface whose texture
// seams it keeps.
struct Simplifiable {
    GltfMesh vertices;  // level 0's attributes at the merged vertices; no indices
    std::vector<unsigned> indices;
};

Simplifiable simplifiable(const GltfMesh& full, bool textured) {
    const std::vector<glm::vec3> positions = mesh::coincidentPointsMerged(full.positions);
    std::vector<meshopt_Stream> streams{{positions.data(), sizeof(glm::vec3), sizeof(glm::vec3)}};
    if (textured && full.hasUvs()) streams.push_back({full.uvs.data(), sizeof(glm::vec2), sizeof(glm::vec2)});
    std::vector<unsigned> remap(full.vertexCount());
    const std::size_t unique = meshopt_generateVertexRemapMulti(remap.data(), full.indices.data(), full.indices.size(),
                                                                full.vertexCount(), streams.data(), streams.size());
    Simplifiable out;
    out.vertices.atlasSize = full.atlasSize;
    auto gather = [&](const auto& values, auto& into) {
        if (values.empty()) return;
        into.resize(unique);
        meshopt_remapVertexBuffer(into.data(), values.data(), values.size(), sizeof(values[0]), remap.data());
    };
    gather(positions, out.vertices.positions);
    gather(full.normals, out.vertices.normals);
    gather(full.tangents, out.vertices.tangents);
    gather(full.uvs, out.vertices.uvs);
    out.indices.resize(full.indices.size());
    meshopt_remapIndexBuffer(out.indices.data(), full.indices.data(), full.indices.size(), remap.data());
    return out;
}

// Level 0 simplified to at most `triangles`, holding only the vertices its triangles use (in
// level 0's order): a level is as light as its triangles, whatever level 0 weighs.
GltfMesh simplified(const Simplifiable& level0, std::size_t triangles) {
    const GltfMesh& all = level0.vertices;
    std::vector<unsigned> indices(level0.indices.size());
    // An error limit of the whole extent: the count decides, the distance is measured afterwards.
    const float noLimit = 1.0f;
    indices.resize(meshopt_simplify(indices.data(), level0.indices.data(), level0.indices.size(), &all.positions[0].x,
                                    all.positions.size(), sizeof(glm::vec3), 3 * triangles, noLimit, 0, nullptr));
    constexpr unsigned kUnused = ~0u;
    std::vector<unsigned> kept(all.vertexCount(), kUnused);
    for (unsigned v : indices) kept[v] = 0;
    GltfMesh out;
    out.atlasSize = all.atlasSize;
    unsigned next = 0;
    for (std::size_t v = 0; v < kept.size(); ++v) {
        if (kept[v] == kUnused) continue;
        kept[v] = next++;
        out.positions.push_back(all.positions[v]);
        if (all.hasNormals()) out.normals.push_back(all.normals[v]);
        if (all.hasTangents()) out.tangents.push_back(all.tangents[v]);
        if (all.hasUvs()) out.uvs.push_back(all.uvs[v]);
    }
    out.indices.resize(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) out.indices[k] = kept[indices[k]];
    return out;
}

double boundingRadius(const GltfMesh& mesh) {
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    return 0.5 * double(glm::length(hi - lo));
}

}  // namespace

LodChain lodChain(const codec::SubdAsset& asset, GltfMesh full, int segments, int count, const ScreenSizeRule& rule) {
    SUBDFIT_CHECK(count >= 1 && count <= kMostLods);
    const SurfaceTextures textures = SurfaceTextures::of(asset.maps);
    const bool textured = textures.baseColor || textures.normalMap || textures.normalTexture;
    LodChain chain{.levels = {}, .boundingRadius = boundingRadius(full)};
    if (count == 1) {
        chain.levels.push_back({.mesh = std::move(full), .segments = segments});
        return chain;
    }
    // What every level is measured against and simplified from, made once.
    const mesh::PolygonMesh reference = triangleMeshOf(full);
    const geometry::SurfaceQueries referenceQueries(reference);
    const Simplifiable level0 = simplifiable(full, textured);
    chain.levels.push_back({.mesh = std::move(full), .segments = segments});
    int coarsestSegments = segments;
    for (int k = 1; k < count; ++k) {
        const LodLevel& previous = chain.levels.back();
        const std::size_t target = previous.mesh.triangleCount() / 2;
        std::vector<LodLevel> candidates;
        int s = coarsestSegments - 1;
        while (s >= 1 && std::size_t(codec::densityAt(asset.cage, s).triangles) > target) --s;
        std::size_t triangles = target;
        if (s >= 1) {
            candidates.push_back({.mesh = surfaceGltfMesh(asset.cage, asset.maps, textures, s), .segments = s});
            triangles = candidates.back().mesh.triangleCount();
        }
        candidates.push_back({.mesh = simplified(level0, triangles), .segments = 0});
        if (candidates.back().mesh.triangleCount() >= previous.mesh.triangleCount()) candidates.pop_back();
        if (candidates.empty()) break;
        for (LodLevel& c : candidates) {
            const auto d = geometry::surfaceDistance(triangleMeshOf(c.mesh), referenceQueries, kErrorSamples);
            c.meanDistance = d.meanDistance;
            c.maxDistance = d.hausdorff;
        }
        auto best = std::min_element(candidates.begin(), candidates.end(), [](const LodLevel& a, const LodLevel& b) {
            return std::tie(a.maxDistance, a.meanDistance) < std::tie(b.maxDistance, b.meanDistance);
        });
        if (best->segments > 0) coarsestSegments = best->segments;
        chain.levels.push_back(std::move(*best));
    }
    for (size_t k = 1; k < chain.levels.size(); ++k) {
        LodLevel& level = chain.levels[k];
        const double size = level.maxDistance > 0.0 ? 2.0 * rule.pixelError * chain.boundingRadius /
                                                          (level.maxDistance * double(rule.screenHeight))
                                                    : 1.0;
        level.screenSize = std::min(size, chain.levels[k - 1].screenSize);
    }
    return chain;
}

}  // namespace subdfit::exporter
