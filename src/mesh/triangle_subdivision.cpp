#include "mesh/triangle_subdivision.h"

#include <array>
#include <cstdint>
#include <unordered_map>

#include "util/error.h"

namespace subdfit::mesh {
namespace {

PolygonMesh splitOnce(const PolygonMesh& in) {
    PolygonMesh out = in;
    out.faceSizes.clear();
    out.faceIndices.clear();
    out.faceMaterials.clear();
    std::unordered_map<std::uint64_t, int> midpoints;
    auto midpoint = [&](int a, int b) {
        const std::uint64_t key = (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
        const auto [it, added] = midpoints.try_emplace(key, out.vertexCount());
        if (!added) return it->second;
        out.positions.push_back(0.5f * (in.positions[size_t(a)] + in.positions[size_t(b)]));
        if (!in.uvs.empty()) out.uvs.push_back(0.5f * (in.uvs[size_t(a)] + in.uvs[size_t(b)]));
        if (!in.colors.empty()) out.colors.push_back(0.5f * (in.colors[size_t(a)] + in.colors[size_t(b)]));
        return it->second;
    };
    for (int f = 0; f < in.faceCount(); ++f) {
        const int* t = &in.faceIndices[3 * size_t(f)];
        const std::array<int, 3> m{midpoint(t[0], t[1]), midpoint(t[1], t[2]), midpoint(t[2], t[0])};
        for (const std::array<int, 3>& child :
             {std::array<int, 3>{t[0], m[0], m[2]}, std::array<int, 3>{m[0], t[1], m[1]},
              std::array<int, 3>{m[2], m[1], t[2]}, m}) {
            out.faceSizes.push_back(3);
            out.faceIndices.insert(out.faceIndices.end(), child.begin(), child.end());
            if (!in.faceMaterials.empty()) out.faceMaterials.push_back(in.faceMaterials[size_t(f)]);
        }
    }
    return out;
}

}  // namespace

PolygonMesh subdividedTriangles(const PolygonMesh& triangles, int times) {
    for (int size : triangles.faceSizes) SUBDFIT_CHECK(size == 3);
    PolygonMesh mesh = triangles;
    mesh.normals.clear();
    for (int k = 0; k < times; ++k) mesh = splitOnce(mesh);
    return mesh;
}

}  // namespace subdfit::mesh
