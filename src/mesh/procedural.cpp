#include "mesh/procedural.h"

#include <glm/geometric.hpp>
#include <cmath>
#include <map>
#include <random>
#include <utility>

namespace subdfit::mesh {

PolygonMesh makeQuadSphere(int n) {
    PolygonMesh mesh;
    mesh.sourcePath = "quad-sphere(" + std::to_string(n) + ")";
    // Vertices are shared along cube edges by keying them on their integer lattice position.
    std::map<std::tuple<int, int, int>, int> index;
    auto vertex = [&](int x, int y, int z) {
        auto [it, inserted] = index.try_emplace({x, y, z}, mesh.vertexCount());
        if (inserted) mesh.positions.push_back(glm::normalize(glm::vec3(x, y, z) / float(n) - 0.5f));
        return it->second;
    };
    // Each side: the lattice point at (a, b) on side (axis, sign); quads wound outwards.
    for (int axis = 0; axis < 3; ++axis)
        for (int sign = 0; sign < 2; ++sign)
            for (int a = 0; a < n; ++a)
                for (int b = 0; b < n; ++b) {
                    auto corner = [&](int da, int db) {
                        int p[3];
                        p[axis] = sign * n;
                        p[(axis + 1) % 3] = a + da;
                        p[(axis + 2) % 3] = b + db;
                        return vertex(p[0], p[1], p[2]);
                    };
                    const int quad[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
                    mesh.faceSizes.push_back(4);
                    for (int k = 0; k < 4; ++k) mesh.faceIndices.push_back(quad[sign ? k : 3 - k]);
                }
    return mesh;
}

PolygonMesh makeQuadGrid(int n, const std::function<float(float, float)>& height) {
    PolygonMesh mesh;
    mesh.sourcePath = "quad-grid(" + std::to_string(n) + ")";
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const float x = -1.0f + 2.0f * float(i) / float(n), y = -1.0f + 2.0f * float(j) / float(n);
            mesh.positions.push_back({x, y, height ? height(x, y) : 0.0f});
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const int a = j * (n + 1) + i;
            mesh.faceSizes.push_back(4);
            mesh.faceIndices.insert(mesh.faceIndices.end(), {a, a + 1, a + n + 2, a + n + 1});
        }
    return mesh;
}

PolygonMesh makeLumpySphere(int subdivisions, float amplitude, std::uint32_t seed, int bumps, float minWidth,
                            float maxWidth) {
    PolygonMesh mesh;
    mesh.sourcePath = "lumpy-sphere";
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    mesh.positions = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                      {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    std::vector<int> tris = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                             4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                             6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    for (auto& p : mesh.positions) p = glm::normalize(p);
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<int, int>, int> midpoints;
        auto midpoint = [&](int a, int b) {
            auto [it, inserted] = midpoints.try_emplace({std::min(a, b), std::max(a, b)}, mesh.vertexCount());
            if (inserted) mesh.positions.push_back(glm::normalize(mesh.positions[a] + mesh.positions[b]));
            return it->second;
        };
        std::vector<int> finer;
        for (size_t f = 0; f < tris.size(); f += 3) {
            const int a = tris[f], b = tris[f + 1], c = tris[f + 2];
            const int ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            finer.insert(finer.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        tris = std::move(finer);
    }
    // Smooth bumps: r(d) = 1 + amplitude Σ_k h_k exp(−(1 − d·c_k) / w_k).
    std::mt19937 rng(seed);
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    struct Bump {
        glm::vec3 centre;
        float height, width;
    };
    std::vector<Bump> lumps;
    for (int k = 0; k < bumps; ++k)
        lumps.push_back({glm::normalize(glm::vec3(normal(rng), normal(rng), normal(rng))),
                         (uniform(rng) < 0.5f ? -1.0f : 1.0f) * (0.5f + 0.5f * uniform(rng)),
                         minWidth + (maxWidth - minWidth) * uniform(rng)});
    for (auto& p : mesh.positions) {
        float r = 1.0f;
        for (const auto& bump : lumps)
            r += amplitude * bump.height * std::exp(-(1.0f - glm::dot(p, bump.centre)) / bump.width);
        p *= r;
    }
    mesh.faceSizes.assign(tris.size() / 3, 3);
    mesh.faceIndices = std::move(tris);
    return mesh;
}

}  // namespace subdfit::mesh
