#include "simplify/remesh/split_long_edges.h"

#include <algorithm>
#include <array>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace subdfit::simplify::remesh {

mesh::PolygonMesh splitLongEdges(const mesh::PolygonMesh& triangles, float longest) {
    mesh::PolygonMesh mesh = triangles;
    for (int pass = 0; pass < 32; ++pass) {
        std::unordered_map<std::uint64_t, int> midpoint;  // split edge → its new vertex
        auto key = [](int a, int b) {
            return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
        };
        for (size_t c = 0; c < mesh.faceIndices.size(); ++c) {
            const int a = mesh.faceIndices[c], b = mesh.faceIndices[c - c % 3 + (c + 1) % 3];
            if (glm::distance(mesh.positions[size_t(a)], mesh.positions[size_t(b)]) > longest &&
                !midpoint.count(key(a, b))) {
                midpoint[key(a, b)] = mesh.vertexCount();
                mesh.positions.push_back(0.5f * (mesh.positions[size_t(a)] + mesh.positions[size_t(b)]));
            }
        }
        if (midpoint.empty()) break;
        std::vector<int> indices;
        indices.reserve(mesh.faceIndices.size() * 2);
        auto add = [&](int a, int b, int c) { indices.insert(indices.end(), {a, b, c}); };
        for (size_t f = 0; f < mesh.faceIndices.size(); f += 3) {
            std::array<int, 3> v{mesh.faceIndices[f], mesh.faceIndices[f + 1], mesh.faceIndices[f + 2]};
            std::array<int, 3> m;  // midpoint of edge k (v[k] → v[k+1]), or -1
            int splits = 0;
            for (int k = 0; k < 3; ++k) {
                const auto it = midpoint.find(key(v[size_t(k)], v[size_t((k + 1) % 3)]));
                m[size_t(k)] = it == midpoint.end() ? -1 : it->second;
                splits += it != midpoint.end();
            }
            if (splits == 0) {
                add(v[0], v[1], v[2]);
            } else if (splits == 3) {
                add(v[0], m[0], m[2]), add(v[1], m[1], m[0]), add(v[2], m[2], m[1]), add(m[0], m[1], m[2]);
            } else {
                // Rotate so that edge 0 is split and, with two splits, edge 1 too.
                int r = 0;
                while (m[size_t(r)] < 0 || (splits == 2 && m[size_t((r + 1) % 3)] < 0)) ++r;
                std::rotate(v.begin(), v.begin() + r, v.end());
                std::rotate(m.begin(), m.begin() + r, m.end());
                if (splits == 1) {
                    add(v[0], m[0], v[2]), add(m[0], v[1], v[2]);
                } else {  // edges 0 and 1 split: the corner v[1] cut off, the rest in two
                    add(m[0], v[1], m[1]), add(v[0], m[0], m[1]), add(v[0], m[1], v[2]);
                }
            }
        }
        mesh.faceIndices = std::move(indices);
        mesh.faceSizes.assign(mesh.faceIndices.size() / 3, 3);
    }
    return mesh;
}

}  // namespace subdfit::simplify::remesh
