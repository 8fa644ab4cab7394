#include "simplify/remesh/quad_extraction.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "simplify/remesh/cross_field.h"
#include "simplify/remesh/polygon_repair.h"
#include "util/disjoint_sets.h"

namespace subdfit::simplify::remesh {
namespace {

// Two leftover triangles make a quad across an edge at least this long against their others (a
// square's diagonal is 1.41 its sides; a flat rhombus's short diagonal is less than 1).
constexpr float kShortestDiagonal = 1.0f;

std::uint64_t edgeKey(int a, int b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
}

struct Triangle {
    std::array<int, 3> v;
    int support = 0;  // input triangles that made it
    bool alive = true;
};

// Drops triangles until every edge has at most two, running it opposite ways: at an edge with
// more, the best-supported triangle stays and then the best-supported one that runs it the
// other way.
void dropOverlaps(std::vector<Triangle>& triangles) {
    for (int round = 0; round < 4; ++round) {
        std::unordered_map<std::uint64_t, std::vector<int>> uses;
        for (int t = 0; t < int(triangles.size()); ++t)
            if (triangles[size_t(t)].alive)
                for (int k = 0; k < 3; ++k)
                    uses[edgeKey(triangles[size_t(t)].v[size_t(k)], triangles[size_t(t)].v[size_t((k + 1) % 3)])]
                        .push_back(t);
        bool changed = false;
        for (auto& [key, list] : uses) {
            const int a = int(key >> 32), b = int(std::uint32_t(key));
            auto forward = [&](int t) {  // runs the edge from its smaller vertex a to b
                const auto& v = triangles[size_t(t)].v;
                for (int k = 0; k < 3; ++k)
                    if (v[size_t(k)] == a && v[size_t((k + 1) % 3)] == b) return true;
                return false;
            };
            if (list.size() <= 1 || (list.size() == 2 && forward(list[0]) != forward(list[1]))) continue;
            std::stable_sort(list.begin(), list.end(),
                             [&](int x, int y) { return triangles[size_t(x)].support > triangles[size_t(y)].support; });
            const bool firstForward = forward(list[0]);
            bool partnerKept = false;
            for (size_t i = 1; i < list.size(); ++i) {
                if (!partnerKept && forward(list[i]) != firstForward) {
                    partnerKept = true;
                    continue;
                }
                triangles[size_t(list[i])].alive = false;
                changed = true;
            }
        }
        if (!changed) return;
    }
}

// The faces of the surviving dual triangles: pairs across a diagonal of the lattice (the
// regions' steps voted so), best-supported first; then, of the triangles left (where the field
// turns about a singularity), pairs across their longest edge; then the triangles left.
Polygons pairedIntoQuads(const std::vector<Triangle>& dual, const std::unordered_map<std::uint64_t, int>& diagonalVotes,
                         const std::vector<glm::vec3>& regionPosition) {
    std::unordered_map<std::uint64_t, std::vector<int>> edgeTriangles;
    for (int t = 0; t < int(dual.size()); ++t)
        if (dual[size_t(t)].alive)
            for (int k = 0; k < 3; ++k)
                edgeTriangles[edgeKey(dual[size_t(t)].v[size_t(k)], dual[size_t(t)].v[size_t((k + 1) % 3)])].push_back(
                    t);
    struct Diagonal {
        float score;
        int t0, t1;
        std::uint64_t key;
    };
    std::vector<char> paired(dual.size(), 0);
    Polygons faces;
    auto pairUp = [&](std::vector<Diagonal>& diagonals) {
        std::sort(diagonals.begin(), diagonals.end(), [](const Diagonal& x, const Diagonal& y) {
            return x.score != y.score ? x.score > y.score : x.key < y.key;
        });
        for (const Diagonal& d : diagonals) {
            if (paired[size_t(d.t0)] || paired[size_t(d.t1)]) continue;
            paired[size_t(d.t0)] = paired[size_t(d.t1)] = 1;
            // t0 = (a, b, x) rotated so that it runs the diagonal a → b; t1 runs b → a to its y.
            const int a = int(d.key >> 32), b = int(std::uint32_t(d.key));
            std::array<int, 3> v0 = dual[size_t(d.t0)].v, v1 = dual[size_t(d.t1)].v;
            while (!(v0[0] == a && v0[1] == b) && !(v0[0] == b && v0[1] == a))
                std::rotate(v0.begin(), v0.begin() + 1, v0.end());
            while (!(v1[0] == v0[1] && v1[1] == v0[0])) std::rotate(v1.begin(), v1.begin() + 1, v1.end());
            faces.push_back({v0[0], v1[2], v0[1], v0[2]});
        }
    };
    std::vector<Diagonal> diagonals;
    for (const auto& [key, list] : edgeTriangles)
        if (const auto votes = diagonalVotes.find(key);
            list.size() == 2 && votes != diagonalVotes.end() && votes->second > 0)
            diagonals.push_back(
                {float(dual[size_t(list[0])].support + dual[size_t(list[1])].support), list[0], list[1], key});
    pairUp(diagonals);
    diagonals.clear();
    auto length = [&](int a, int b) { return glm::distance(regionPosition[size_t(a)], regionPosition[size_t(b)]); };
    for (const auto& [key, list] : edgeTriangles) {
        if (list.size() != 2 || paired[size_t(list[0])] || paired[size_t(list[1])]) continue;
        const int a = int(key >> 32), b = int(std::uint32_t(key));
        float longestOther = 0.0f;
        for (int t : list)
            for (int v : dual[size_t(t)].v)
                if (v != a && v != b) longestOther = std::max({longestOther, length(a, v), length(b, v)});
        const float score = length(a, b) / std::max(longestOther, 1e-30f);
        if (score > kShortestDiagonal) diagonals.push_back({score, list[0], list[1], key});
    }
    pairUp(diagonals);
    for (size_t t = 0; t < dual.size(); ++t)
        if (dual[t].alive && !paired[t]) faces.push_back({dual[t].v.begin(), dual[t].v.end()});

    return faces;
}

}  // namespace

ExtractedMesh extractQuads(const mesh::PolygonMesh& triangles, const GraphLevel& finest,
                           const std::vector<glm::vec3>& orientation, const std::vector<glm::vec3>& position) {
    const int n = finest.size();
    auto step = [&](int a, int b) {
        return latticeStep(position[size_t(a)], orientation[size_t(a)], finest.normals[size_t(a)], position[size_t(b)],
                           0.5f * (finest.scales[size_t(a)] + finest.scales[size_t(b)]));
    };

    // The regions: samples joined through neighbours on the same lattice point.
    DisjointSets sets(n);
    for (int a = 0; a < n; ++a)
        for (int k = finest.offsets[size_t(a)]; k < finest.offsets[size_t(a) + 1]; ++k) {
            const LatticeStep s = step(a, finest.neighbors[size_t(k)]);
            if (s.i == 0 && s.j == 0) sets.join(a, finest.neighbors[size_t(k)]);
        }
    std::vector<int> region(size_t(n), -1);
    int regions = 0;
    for (int a = 0; a < n; ++a)
        if (sets.find(a) == a) region[size_t(a)] = regions++;
    for (int a = 0; a < n; ++a) region[size_t(a)] = region[size_t(sets.find(a))];

    // Whether two regions meet across a diagonal of the lattice: the majority of their samples' steps.
    std::unordered_map<std::uint64_t, int> diagonalVotes;
    for (int a = 0; a < n; ++a)
        for (int k = finest.offsets[size_t(a)]; k < finest.offsets[size_t(a) + 1]; ++k) {
            const int b = finest.neighbors[size_t(k)];
            if (region[size_t(a)] == region[size_t(b)]) continue;
            const LatticeStep s = step(a, b);
            diagonalVotes[edgeKey(region[size_t(a)], region[size_t(b)])] +=
                std::abs(s.i) == 1 && std::abs(s.j) == 1 ? 1 : -1;
        }

    std::vector<Triangle> dual;
    std::map<std::array<int, 3>, int> dualIndex;
    for (int f = 0; f < triangles.faceCount(); ++f) {
        std::array<int, 3> v;
        for (int k = 0; k < 3; ++k) v[size_t(k)] = region[size_t(triangles.faceIndices[size_t(3 * f + k)])];
        if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2]) continue;
        std::array<int, 3> sorted = v;
        std::sort(sorted.begin(), sorted.end());
        const auto [it, added] = dualIndex.emplace(sorted, int(dual.size()));
        if (added) dual.push_back({v});
        ++dual[size_t(it->second)].support;
    }
    dropOverlaps(dual);

    // Each region's vertex at its mean lattice point.
    std::vector<glm::vec3> regionPosition(size_t(regions), glm::vec3(0.0f)),
        normalSum(size_t(regions), glm::vec3(0.0f));
    std::vector<float> weight(size_t(regions), 0.0f);
    for (int a = 0; a < n; ++a) {
        const float w = std::max(finest.areas[size_t(a)], 1e-30f);
        regionPosition[size_t(region[size_t(a)])] += w * position[size_t(a)];
        normalSum[size_t(region[size_t(a)])] += w * finest.normals[size_t(a)];
        weight[size_t(region[size_t(a)])] += w;
    }
    for (int r = 0; r < regions; ++r) regionPosition[size_t(r)] /= weight[size_t(r)];

    Polygons faces = pairedIntoQuads(dual, diagonalVotes, regionPosition);

    // A vertex where dropped triangles left two fans becomes two; the holes they left inside the
    // input close (a region that holds a sample of the input's boundary is on its boundary).
    const std::vector<int> copiedFrom = splitFans(faces, regions);
    std::vector<char> inside(size_t(regions), 1);
    std::unordered_map<std::uint64_t, int> inputEdgeUses;
    for (int f = 0; f < triangles.faceCount(); ++f)
        for (int k = 0; k < 3; ++k)
            ++inputEdgeUses[edgeKey(triangles.faceIndices[size_t(3 * f + k)],
                                    triangles.faceIndices[size_t(3 * f + (k + 1) % 3)])];
    for (const auto& [key, uses] : inputEdgeUses)
        if (uses != 2)
            inside[size_t(region[size_t(key >> 32)])] = inside[size_t(region[size_t(std::uint32_t(key))])] = 0;
    for (int r : copiedFrom) inside.push_back(inside[size_t(r)]);
    closeHoles(faces, inside);

    // The vertices the faces use.
    auto regionOf = [&](int v) { return v < regions ? v : copiedFrom[size_t(v - regions)]; };
    std::vector<int> index(size_t(regions) + copiedFrom.size(), -1);
    ExtractedMesh out;
    out.mesh.sourcePath = triangles.sourcePath;
    for (const auto& f : faces) {
        out.mesh.faceSizes.push_back(int(f.size()));
        for (int v : f) {
            if (index[size_t(v)] < 0) {
                const int r = regionOf(v);
                index[size_t(v)] = out.mesh.vertexCount();
                out.mesh.positions.push_back(regionPosition[size_t(r)]);
                const float length = glm::length(normalSum[size_t(r)]);
                out.normals.push_back(length > 0.0f ? normalSum[size_t(r)] / length : glm::vec3(0, 0, 1));
            }
            out.mesh.faceIndices.push_back(index[size_t(v)]);
        }
    }
    return out;
}

}  // namespace subdfit::simplify::remesh
