#include "simplify/remesh/quad_extraction.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <map>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "simplify/remesh/cross_field.h"

namespace subdfit::simplify::remesh {
namespace {

constexpr int kLargestClosedHole = 6;  // corners of a hole closed by a polygon; larger ones are the input's
// Two leftover triangles make a quad across an edge at least this long against their others (a
// square's diagonal is 1.41 its sides; a flat rhombus's short diagonal is less than 1).
constexpr float kShortestDiagonal = 1.0f;

class DisjointSets {
public:
    explicit DisjointSets(int n) : parent_(size_t(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
    int find(int x) {
        while (parent_[size_t(x)] != x) x = parent_[size_t(x)] = parent_[size_t(parent_[size_t(x)])];
        return x;
    }
    void join(int a, int b) {
        a = find(a), b = find(b);
        if (a != b) parent_[size_t(std::max(a, b))] = std::min(a, b);
    }

private:
    std::vector<int> parent_;
};

std::uint64_t edgeKey(int a, int b) { return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b)); }

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
                for (int k = 0; k < 3; ++k) uses[edgeKey(triangles[size_t(t)].v[size_t(k)], triangles[size_t(t)].v[size_t((k + 1) % 3)])].push_back(t);
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
            std::stable_sort(list.begin(), list.end(), [&](int x, int y) { return triangles[size_t(x)].support > triangles[size_t(y)].support; });
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

// The boundary loops of the faces with few corners, as polygons that close them.
std::vector<std::vector<int>> smallHoles(const std::vector<std::vector<int>>& faces) {
    std::unordered_map<std::uint64_t, int> directed;  // (a → b) → count
    auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
    for (const auto& f : faces)
        for (size_t k = 0; k < f.size(); ++k) ++directed[key(f[k], f[(k + 1) % f.size()])];
    std::unordered_map<int, std::vector<int>> next;  // the hole runs each boundary edge backwards
    for (const auto& [k, count] : directed) {
        const int a = int(k >> 32), b = int(std::uint32_t(k));
        if (!directed.count(key(b, a))) next[b].push_back(a);
    }
    std::vector<std::vector<int>> holes;
    std::unordered_map<int, char> used;
    for (const auto& [start, outgoing] : next) {
        if (outgoing.size() != 1 || used[start]) continue;
        std::vector<int> loop{start};
        int at = outgoing[0];
        bool simple = true;
        while (at != start && simple && int(loop.size()) <= kLargestClosedHole) {
            const auto it = next.find(at);
            simple = it != next.end() && it->second.size() == 1 && !used[at];
            loop.push_back(at);
            if (simple) at = it->second[0];
        }
        if (!simple || at != start || loop.size() < 3 || int(loop.size()) > kLargestClosedHole) continue;
        for (int v : loop) used[v] = 1;
        holes.push_back(std::move(loop));
    }
    return holes;
}

}  // namespace

ExtractedMesh extractQuads(const mesh::PolygonMesh& triangles, const GraphLevel& finest,
                           const std::vector<glm::vec3>& orientation, const std::vector<glm::vec3>& position, float scale) {
    const int n = finest.size();
    auto step = [&](int a, int b) { return latticeStep(position[size_t(a)], orientation[size_t(a)], finest.normals[size_t(a)], position[size_t(b)], scale); };

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
            diagonalVotes[edgeKey(region[size_t(a)], region[size_t(b)])] += std::abs(s.i) == 1 && std::abs(s.j) == 1 ? 1 : -1;
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
    std::vector<glm::vec3> regionPosition(size_t(regions), glm::vec3(0.0f)), normalSum(size_t(regions), glm::vec3(0.0f));
    std::vector<float> weight(size_t(regions), 0.0f);
    for (int a = 0; a < n; ++a) {
        const float w = std::max(finest.areas[size_t(a)], 1e-30f);
        regionPosition[size_t(region[size_t(a)])] += w * position[size_t(a)];
        normalSum[size_t(region[size_t(a)])] += w * finest.normals[size_t(a)];
        weight[size_t(region[size_t(a)])] += w;
    }
    for (int r = 0; r < regions; ++r) regionPosition[size_t(r)] /= weight[size_t(r)];

    // Quads: triangle pairs across a diagonal of the lattice, best-supported first; then, of the
    // triangles left (where the field turns about a singularity), pairs across their longest edge.
    std::unordered_map<std::uint64_t, std::vector<int>> edgeTriangles;
    for (int t = 0; t < int(dual.size()); ++t)
        if (dual[size_t(t)].alive)
            for (int k = 0; k < 3; ++k) edgeTriangles[edgeKey(dual[size_t(t)].v[size_t(k)], dual[size_t(t)].v[size_t((k + 1) % 3)])].push_back(t);
    struct Diagonal {
        float score;
        int t0, t1;
        std::uint64_t key;
    };
    std::vector<char> paired(dual.size(), 0);
    std::vector<std::vector<int>> faces;
    auto pairUp = [&](std::vector<Diagonal>& diagonals) {
        std::sort(diagonals.begin(), diagonals.end(), [](const Diagonal& x, const Diagonal& y) { return x.score != y.score ? x.score > y.score : x.key < y.key; });
        for (const Diagonal& d : diagonals) {
            if (paired[size_t(d.t0)] || paired[size_t(d.t1)]) continue;
            paired[size_t(d.t0)] = paired[size_t(d.t1)] = 1;
            // t0 = (a, b, x) rotated so that it runs the diagonal a → b; t1 runs b → a to its y.
            const int a = int(d.key >> 32), b = int(std::uint32_t(d.key));
            std::array<int, 3> v0 = dual[size_t(d.t0)].v, v1 = dual[size_t(d.t1)].v;
            while (!(v0[0] == a && v0[1] == b) && !(v0[0] == b && v0[1] == a)) std::rotate(v0.begin(), v0.begin() + 1, v0.end());
            while (!(v1[0] == v0[1] && v1[1] == v0[0])) std::rotate(v1.begin(), v1.begin() + 1, v1.end());
            faces.push_back({v0[0], v1[2], v0[1], v0[2]});
        }
    };
    std::vector<Diagonal> diagonals;
    for (const auto& [key, list] : edgeTriangles)
        if (list.size() == 2 && diagonalVotes[key] > 0)
            diagonals.push_back({float(dual[size_t(list[0])].support + dual[size_t(list[1])].support), list[0], list[1], key});
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
    for (auto& hole : smallHoles(faces)) faces.push_back(std::move(hole));

    // The vertices the faces use.
    std::vector<int> index(size_t(regions), -1);
    ExtractedMesh out;
    out.mesh.sourcePath = triangles.sourcePath;
    for (const auto& f : faces) {
        out.mesh.faceSizes.push_back(int(f.size()));
        for (int r : f) {
            if (index[size_t(r)] < 0) {
                index[size_t(r)] = out.mesh.vertexCount();
                out.mesh.positions.push_back(regionPosition[size_t(r)]);
                const float length = glm::length(normalSum[size_t(r)]);
                out.normals.push_back(length > 0.0f ? normalSum[size_t(r)] / length : glm::vec3(0, 0, 1));
            }
            out.mesh.faceIndices.push_back(index[size_t(r)]);
        }
    }
    return out;
}

bool isManifold(const mesh::PolygonMesh& mesh) {
    // Each directed edge once; the corner that starts it, to walk the fans.
    std::unordered_map<std::uint64_t, int> cornerOf;
    auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
    std::vector<int> faceOf, firstOf;
    for (int f = 0, first = 0; f < mesh.faceCount(); first += mesh.faceSizes[size_t(f)], ++f)
        for (int k = 0; k < mesh.faceSizes[size_t(f)]; ++k) {
            faceOf.push_back(f);
            firstOf.push_back(first);
        }
    auto nextCorner = [&](int c) {
        const int first = firstOf[size_t(c)], size = mesh.faceSizes[size_t(faceOf[size_t(c)])];
        return first + (c - first + 1) % size;
    };
    auto previousCorner = [&](int c) {
        const int first = firstOf[size_t(c)], size = mesh.faceSizes[size_t(faceOf[size_t(c)])];
        return first + (c - first + size - 1) % size;
    };
    for (int c = 0; c < int(mesh.faceIndices.size()); ++c) {
        const int a = mesh.faceIndices[size_t(c)], b = mesh.faceIndices[size_t(nextCorner(c))];
        if (a == b || !cornerOf.emplace(key(a, b), c).second) return false;
    }
    // Around each vertex: from any corner, turn through the faces (both ways where there is a
    // boundary) and count; one fan reaches every corner of the vertex.
    std::vector<int> cornersAt(size_t(mesh.vertexCount()), 0), someCorner(size_t(mesh.vertexCount()), -1);
    for (int c = 0; c < int(mesh.faceIndices.size()); ++c) {
        ++cornersAt[size_t(mesh.faceIndices[size_t(c)])];
        someCorner[size_t(mesh.faceIndices[size_t(c)])] = c;
    }
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        if (someCorner[size_t(v)] < 0) continue;
        int reached = 1;
        // Clockwise: the corner of v in the face across the edge entering v's corner.
        const int start = someCorner[size_t(v)];
        int c = start;
        bool closed = false;
        while (true) {
            const int previous = mesh.faceIndices[size_t(previousCorner(c))];
            const auto it = cornerOf.find(key(v, previous));  // the face running v → previous
            if (it == cornerOf.end()) break;
            c = it->second;
            if (c == start) {
                closed = true;
                break;
            }
            if (++reached > cornersAt[size_t(v)]) return false;
        }
        if (!closed) {
            c = start;
            while (true) {
                const int next = mesh.faceIndices[size_t(nextCorner(c))];
                const auto it = cornerOf.find(key(next, v));  // the face running next → v
                if (it == cornerOf.end()) break;
                c = nextCorner(it->second);
                if (++reached > cornersAt[size_t(v)]) return false;
            }
        }
        if (reached != cornersAt[size_t(v)]) return false;
    }
    return true;
}

}  // namespace subdfit::simplify::remesh
