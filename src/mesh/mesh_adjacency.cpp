#include "mesh/mesh_adjacency.h"

#include <algorithm>

#include "util/error.h"

namespace subdfit::mesh {

VertexAdjacency vertexAdjacency(const PolygonMesh& mesh) {
    const size_t vertexCount = mesh.positions.size();

    // Pass 1: every face edge, both directions, bucketed by vertex (with repeats).
    std::vector<int> start(vertexCount + 1, 0);
    auto forEachEdge = [&](auto&& visit) {
        size_t first = 0;
        for (const int n : mesh.faceSizes) {
            SUBDFIT_CHECK(first + size_t(n) <= mesh.faceIndices.size());
            for (int k = 0; k < n; ++k) {
                const int a = mesh.faceIndices[first + size_t(k)];
                const int b = mesh.faceIndices[first + size_t((k + 1) % n)];
                SUBDFIT_CHECK(a >= 0 && size_t(a) < vertexCount && b >= 0 && size_t(b) < vertexCount);
                if (a != b) visit(a, b);
            }
            first += size_t(n);
        }
    };
    forEachEdge([&](int a, int b) { ++start[size_t(a) + 1], ++start[size_t(b) + 1]; });
    for (size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
    std::vector<int> all(static_cast<size_t>(start[vertexCount]));
    std::vector<int> fill(start.begin(), start.end() - 1);
    forEachEdge([&](int a, int b) {
        all[size_t(fill[size_t(a)]++)] = b;
        all[size_t(fill[size_t(b)]++)] = a;
    });

    // Pass 2: sort each bucket and keep its unique entries.
    VertexAdjacency adjacency;
    adjacency.offsets.assign(vertexCount + 1, 0);
    adjacency.neighbors.reserve(all.size() / 2);
    for (size_t v = 0; v < vertexCount; ++v) {
        const auto begin = all.begin() + start[v], end = all.begin() + start[v + 1];
        std::sort(begin, end);
        adjacency.neighbors.insert(adjacency.neighbors.end(), begin, std::unique(begin, end));
        adjacency.offsets[v + 1] = int(adjacency.neighbors.size());
    }
    return adjacency;
}

}  // namespace subdfit::mesh
