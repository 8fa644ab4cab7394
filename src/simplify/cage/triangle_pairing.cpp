#include "simplify/cage/triangle_pairing.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "util/error.h"

namespace subdfit::simplify {
namespace {

using Edge = std::pair<int, int>;  // (smaller, larger) vertex

// The longest augmenting path tried, in joins that swap.
constexpr int kMostPathSwaps = 8;

// A candidate join: triangles f and g across their edge, the quad it makes in f's winding.
struct Join {
    float cost;
    int f, g;
    std::array<int, 4> quad;
};

float angleBetween(glm::vec3 a, glm::vec3 b) {
    const float la = glm::length(a), lb = glm::length(b);
    if (!(la > 0.0f && lb > 0.0f)) return float(M_PI);  // a degenerate corner never qualifies
    return std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
}

// The quad's worst corner skew and its fold, in degrees.
std::pair<float, float> shapeOf(const mesh::PolygonMesh& mesh, const std::array<int, 4>& quad) {
    std::array<glm::vec3, 4> p;
    for (int k = 0; k < 4; ++k) p[size_t(k)] = mesh.positions[size_t(quad[size_t(k)])];
    float skew = 0.0f;
    for (int k = 0; k < 4; ++k) {
        const glm::vec3 corner = p[size_t(k)];
        const float angle = angleBetween(p[size_t((k + 3) % 4)] - corner, p[size_t((k + 1) % 4)] - corner);
        skew = std::max(skew, std::abs(glm::degrees(angle) - 90.0f));
    }
    // The triangles either side of the dropped diagonal quad[0]-quad[2].
    const glm::vec3 n1 = glm::cross(p[1] - p[0], p[2] - p[0]), n2 = glm::cross(p[2] - p[0], p[3] - p[0]);
    return {skew, glm::degrees(angleBetween(n1, n2))};
}

}  // namespace

mesh::PolygonMesh pairTriangles(const mesh::PolygonMesh& triangles, const TrianglePairingOptions& options) {
    const int faces = triangles.faceCount();
    for (int f = 0; f < faces; ++f) SUBDFIT_CHECK(triangles.faceSizes[size_t(f)] == 3);
    std::set<Edge> creased;
    for (const mesh::Crease& c : triangles.tags.creases)
        if (c.sharpness > 0.0f) creased.insert(std::minmax(c.v0, c.v1));
    const std::set<int> holes(triangles.tags.holes.begin(), triangles.tags.holes.end());

    // Each edge's faces and their corner opposite it.
    struct Side {
        int face, from, opposite;  // the face runs from -> (the other end) along the edge
    };
    std::map<Edge, std::vector<Side>> sides;
    auto corner = [&](int f, int k) { return triangles.faceIndices[size_t(3 * f + (k % 3))]; };
    for (int f = 0; f < faces; ++f)
        for (int k = 0; k < 3; ++k)
            sides[std::minmax(corner(f, k), corner(f, k + 1))].push_back({f, corner(f, k), corner(f, k + 2)});

    std::vector<Join> joins;
    for (const auto& [edge, at] : sides) {
        if (at.size() != 2 || creased.contains(edge)) continue;
        const Side &a = at[0], &b = at[1];
        if (a.from == b.from) continue;                                  // wound opposite ways
        if (holes.contains(a.face) != holes.contains(b.face)) continue;  // a hole's rim
        // a runs p -> q, so a is (p, q, r) and b is (q, p, s): the quad q r p s in a's winding.
        const int p = a.from, q = p == edge.first ? edge.second : edge.first;
        const std::array<int, 4> quad{q, a.opposite, p, b.opposite};
        if (a.opposite == b.opposite) continue;
        const auto [skew, fold] = shapeOf(triangles, quad);
        if (skew > options.mostCornerSkew || fold > options.mostFold) continue;
        joins.push_back({skew + fold, a.face, b.face, quad});
    }
    std::sort(joins.begin(), joins.end(), [](const Join& x, const Join& y) {
        return x.cost != y.cost ? x.cost < y.cost : std::tie(x.f, x.g) < std::tie(y.f, y.g);
    });
    // Greedy, best first; then each triangle left alone looks for an augmenting path: a join to a
    // joined neighbour, whose partner joins onwards, ... until a lone triangle is reached, and
    // every join along it swaps (one more pair). The greedy order leaves about a fifth of a
    // decimated mesh's triangles alone; short paths pair most of them.
    std::vector<std::vector<const Join*>> joinsOf(static_cast<size_t>(faces));
    for (const Join& j : joins) {
        joinsOf[size_t(j.f)].push_back(&j);
        joinsOf[size_t(j.g)].push_back(&j);
    }
    auto other = [](const Join* j, int f) { return j->f == f ? j->g : j->f; };
    std::vector<const Join*> joinOf(size_t(faces), nullptr);
    auto partner = [&](int f) { return joinOf[size_t(f)] ? other(joinOf[size_t(f)], f) : -1; };
    auto join = [&](const Join* j) { joinOf[size_t(j->f)] = joinOf[size_t(j->g)] = j; };
    for (const Join& j : joins)
        if (!joinOf[size_t(j.f)] && !joinOf[size_t(j.g)]) join(&j);
    std::vector<int> visited(size_t(faces), -1);
    std::vector<const Join*> path;
    // From `f` (lone, or whose partner is being taken), a path of at most `depth` more swaps.
    std::function<bool(int, int, int)> augment = [&](int f, int depth, int search) {
        visited[size_t(f)] = search;
        for (const Join* a : joinsOf[size_t(f)]) {
            const int u = other(a, f);
            if (visited[size_t(u)] == search) continue;
            const int w = partner(u);
            if (w < 0) {
                path.push_back(a);
                return true;
            }
            if (depth == 0 || visited[size_t(w)] == search) continue;
            visited[size_t(u)] = search;
            path.push_back(a);
            if (augment(w, depth - 1, search)) return true;
            path.pop_back();
        }
        return false;
    };
    for (int depth : {1, 2, 4, kMostPathSwaps})
        for (int f = 0; f < faces; ++f) {
            if (joinOf[size_t(f)] || joinsOf[size_t(f)].empty()) continue;
            path.clear();
            if (augment(f, depth, f + depth * faces))
                for (const Join* j : path) join(j);
        }

    mesh::PolygonMesh out;
    out.positions = triangles.positions;
    out.tags = triangles.tags;
    out.tags.holes.clear();
    out.sourcePath = triangles.sourcePath;
    for (int f = 0; f < faces; ++f) {
        if (partner(f) >= 0 && partner(f) < f) continue;  // joined to an earlier one
        if (holes.contains(f)) out.tags.holes.push_back(out.faceCount());
        if (const Join* j = joinOf[size_t(f)]) {
            out.faceSizes.push_back(4);
            out.faceIndices.insert(out.faceIndices.end(), j->quad.begin(), j->quad.end());
        } else {
            out.faceSizes.push_back(3);
            for (int k = 0; k < 3; ++k) out.faceIndices.push_back(corner(f, k));
        }
    }
    return out;
}

}  // namespace subdfit::simplify
