#include "simplify/cage/quad_pairing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "util/error.h"

namespace subdfit::simplify {
namespace {

std::uint64_t edgeKey(int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); }

struct Pair {
    float score;
    int t1, t2;
    int quad[4];
};

// The angle at corner b of the polyline a-b-c, in degrees (180 for a degenerate one).
float cornerDegrees(glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 u = a - b, v = c - b;
    const float lengths = glm::length(u) * glm::length(v);
    if (!(lengths > 0.0f)) return 180.0f;
    return glm::degrees(std::acos(std::clamp(glm::dot(u, v) / lengths, -1.0f, 1.0f)));
}

}  // namespace

mesh::PolygonMesh pairIntoQuads(const mesh::PolygonMesh& triangles, const QuadPairing& pairing) {
    SUBDFIT_CHECK(triangles.faceIndices.size() == 3 * triangles.faceSizes.size() && triangles.tags.holes.empty());
    const int faces = triangles.faceCount();
    const auto& p = triangles.positions;
    const int* corners = triangles.faceIndices.data();

    std::unordered_set<std::uint64_t> creased;
    for (const mesh::Crease& c : triangles.tags.creases) creased.insert({edgeKey(c.v0, c.v1), edgeKey(c.v1, c.v0)});
    std::unordered_map<std::uint64_t, int> faceOfEdge;  // directed edge -> its triangle
    for (int t = 0; t < faces; ++t)
        for (int k = 0; k < 3; ++k)
            if (!faceOfEdge.emplace(edgeKey(corners[3 * t + k], corners[3 * t + (k + 1) % 3]), t).second)
                faceOfEdge[edgeKey(corners[3 * t + k], corners[3 * t + (k + 1) % 3])] = -1;  // not manifold: never paired

    const float cosFold = std::cos(glm::radians(pairing.mostFoldDegrees));
    std::vector<Pair> pairs;
    for (int t = 0; t < faces; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = corners[3 * t + k], b = corners[3 * t + (k + 1) % 3], c = corners[3 * t + (k + 2) % 3];
            const auto twin = faceOfEdge.find(edgeKey(b, a));
            if (twin == faceOfEdge.end() || twin->second <= t || faceOfEdge[edgeKey(a, b)] != t) continue;
            if (creased.count(edgeKey(a, b))) continue;
            const int u = twin->second;
            int d = -1;
            for (int j = 0; j < 3; ++j)
                if (corners[3 * u + j] != a && corners[3 * u + j] != b) d = corners[3 * u + j];
            if (d < 0 || d == c) continue;
            // Triangles (a, b, c) and (b, a, d) make the quad (b, c, a, d).
            const glm::vec3 n1 = glm::cross(p[b] - p[a], p[c] - p[a]), n2 = glm::cross(p[a] - p[b], p[d] - p[b]);
            const float l1 = glm::length(n1), l2 = glm::length(n2);
            if (!(l1 > 0.0f && l2 > 0.0f) || glm::dot(n1, n2) < cosFold * l1 * l2) continue;
            const int quad[4] = {b, c, a, d};
            float worst = 0.0f;
            for (int j = 0; j < 4; ++j) {
                const float angle = cornerDegrees(p[quad[(j + 3) % 4]], p[quad[j]], p[quad[(j + 1) % 4]]);
                if (angle > pairing.mostCornerDegrees) worst = 1e9f;
                worst = std::max(worst, std::abs(angle - 90.0f));
            }
            if (worst > 90.0f) continue;
            const float flat = glm::dot(n1, n2) / (l1 * l2);
            pairs.push_back({(1.0f - worst / 90.0f) * (0.5f + 0.5f * flat), t, u, {b, c, a, d}});
        }
    std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.score > y.score; });

    mesh::PolygonMesh out;
    out.positions = triangles.positions;
    out.tags = triangles.tags;
    out.sourcePath = triangles.sourcePath;
    std::vector<char> paired(size_t(faces), 0);
    for (const Pair& pair : pairs) {
        if (paired[size_t(pair.t1)] || paired[size_t(pair.t2)]) continue;
        paired[size_t(pair.t1)] = paired[size_t(pair.t2)] = 1;
        out.faceSizes.push_back(4);
        out.faceIndices.insert(out.faceIndices.end(), pair.quad, pair.quad + 4);
    }
    for (int t = 0; t < faces; ++t)
        if (!paired[size_t(t)]) {
            out.faceSizes.push_back(3);
            out.faceIndices.insert(out.faceIndices.end(), corners + 3 * t, corners + 3 * t + 3);
        }
    return out;
}

}  // namespace subdfit::simplify
