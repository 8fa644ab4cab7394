#include "geometry/limit_mesh.h"

#include <cmath>
#include <map>
#include <tuple>

#include "subdiv/limit_evaluator.h"

namespace subdfit::geometry {

mesh::PolygonMesh limitMesh(const mesh::PolygonMesh& cage, int segments) {
    const subdiv::LimitEvaluator evaluator(cage);
    mesh::PolygonMesh out;
    out.sourcePath = cage.sourcePath + " (limit surface)";
    // Weld on a lattice far finer than the samples: the same limit point evaluated from two
    // neighbouring patches agrees to rounding, not bit for bit.
    float extent = 0.0f;
    for (const auto& p : cage.positions) extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const float cell = std::max(extent, 1e-30f) * 1e-6f;
    std::map<std::tuple<long long, long long, long long>, int> welded;
    auto vertex = [&](const glm::vec3& p) {
        const auto key = std::make_tuple(std::llround(p.x / cell), std::llround(p.y / cell), std::llround(p.z / cell));
        auto [it, inserted] = welded.try_emplace(key, out.vertexCount());
        if (inserted) out.positions.push_back(p);
        return it->second;
    };
    std::vector<int> grid(size_t(segments + 1) * (segments + 1));
    for (int face = 0; face < evaluator.ptexFaceCount(); ++face) {
        if (!evaluator.hasSurface(face, 0.5f, 0.5f)) continue;
        for (int j = 0; j <= segments; ++j)
            for (int i = 0; i <= segments; ++i) {
                const float u = float(i) / float(segments), v = float(j) / float(segments);
                grid[size_t(j) * (segments + 1) + i] = vertex(evaluator.evaluate(face, u, v, cage.positions).position);
            }
        for (int j = 0; j < segments; ++j)
            for (int i = 0; i < segments; ++i) {
                const int a = grid[size_t(j) * (segments + 1) + i], b = grid[size_t(j) * (segments + 1) + i + 1];
                const int c = grid[size_t(j + 1) * (segments + 1) + i + 1], d = grid[size_t(j + 1) * (segments + 1) + i];
                for (const auto& tri : {std::array<int, 3>{a, b, c}, std::array<int, 3>{a, c, d}}) {
                    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;  // collapsed at a pole
                    out.faceSizes.push_back(3);
                    out.faceIndices.insert(out.faceIndices.end(), tri.begin(), tri.end());
                }
            }
    }
    return out;
}

}  // namespace subdfit::geometry
