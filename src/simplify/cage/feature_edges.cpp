#include "simplify/cage/feature_edges.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <unordered_map>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "mesh/mesh_geometry.h"
#include "mesh/position_map.h"

namespace subdfit::simplify {
namespace {

constexpr float kInfinitelySharp = 10.0f;

float angleBetween(const glm::vec3& a, const glm::vec3& b) {
    return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
}

glm::vec3 unitOr0(const glm::vec3& v) {
    const float length = glm::length(v);
    return length > 0.0f && std::isfinite(length) ? v / length : glm::vec3(0.0f);
}

using Edge = std::pair<int, int>;  // (smaller, larger) vertex index

// Each edge of a triangle mesh with the (up to two) triangles on it and how many there are.
struct EdgeFaces {
    int faces[2] = {-1, -1};
    int count = 0;
};

std::map<Edge, EdgeFaces> edgeFaces(const mesh::PolygonMesh& triangles) {
    std::map<Edge, EdgeFaces> edges;
    for (int f = 0; f < triangles.faceCount(); ++f) {
        const int* v = &triangles.faceIndices[size_t(3 * f)];
        for (int k = 0; k < 3; ++k) {
            EdgeFaces& e = edges[std::minmax(v[k], v[(k + 1) % 3])];
            if (e.count < 2) e.faces[e.count] = f;
            ++e.count;
        }
    }
    return edges;
}

// The reference's hard edges as a graph on its welded vertices, and its sharp boundary corners.
struct Features {
    mesh::PositionMap<int> vertexAt;              // welded vertex of a position
    std::vector<glm::vec3> positions;             // per welded vertex
    std::vector<std::vector<int>> hardNeighbors;  // per welded vertex
    std::vector<char> corner;                     // per welded vertex
};

Features referenceFeatures(const mesh::PolygonMesh& reference, const FeatureAngles& angles) {
    const float hard = glm::radians(angles.edgeDegrees), turning = glm::radians(angles.boundaryDegrees);
    Features features;
    std::vector<int> welded(reference.positions.size());
    for (size_t v = 0; v < reference.positions.size(); ++v) {
        const auto [it, added] = features.vertexAt.emplace(reference.positions[v], int(features.positions.size()));
        if (added) features.positions.push_back(reference.positions[v]);
        welded[v] = it->second;
    }
    const size_t count = features.positions.size();
    features.hardNeighbors.resize(count);
    features.corner.assign(count, 0);

    // Per welded edge, the file's vertices at its ends on each side (one side per triangle).
    struct Side {
        int atFirst, atSecond;
    };
    std::map<Edge, std::vector<Side>> sides;
    for (int f = 0; f < reference.faceCount(); ++f) {
        const int* v = &reference.faceIndices[size_t(3 * f)];
        for (int k = 0; k < 3; ++k) {
            const int a = v[k], b = v[(k + 1) % 3];
            if (welded[size_t(a)] == welded[size_t(b)]) continue;
            const bool inOrder = welded[size_t(a)] < welded[size_t(b)];
            sides[std::minmax(welded[size_t(a)], welded[size_t(b)])].push_back(inOrder ? Side{a, b} : Side{b, a});
        }
    }
    const std::vector<glm::vec3> normals = mesh::shadingNormals(reference);
    auto parts = [&](int u, int w) { return u != w && angleBetween(normals[size_t(u)], normals[size_t(w)]) > hard; };
    std::vector<std::vector<int>> boundaryNeighbors(count);
    for (const auto& [edge, around] : sides) {
        if (around.size() == 1) {
            boundaryNeighbors[size_t(edge.first)].push_back(edge.second);
            boundaryNeighbors[size_t(edge.second)].push_back(edge.first);
        }
        if (around.size() != 2) continue;
        if (!parts(around[0].atFirst, around[1].atFirst) && !parts(around[0].atSecond, around[1].atSecond)) continue;
        features.hardNeighbors[size_t(edge.first)].push_back(edge.second);
        features.hardNeighbors[size_t(edge.second)].push_back(edge.first);
    }
    for (size_t v = 0; v < count; ++v) {
        const auto& around = boundaryNeighbors[v];
        if (around.size() != 2) continue;  // a non-manifold vertex is OpenSubdiv's to handle
        const glm::vec3 in = unitOr0(features.positions[v] - features.positions[size_t(around[0])]),
                        out = unitOr0(features.positions[size_t(around[1])] - features.positions[v]);
        if (in != glm::vec3(0.0f) && out != glm::vec3(0.0f) && angleBetween(in, out) > turning) features.corner[v] = 1;
    }
    return features;
}

// Whether hard edges lead from `from` to `to` within `most` of length (Dijkstra, bounded).
bool hardChain(const Features& features, int from, int to, float most) {
    std::unordered_map<int, float> reached{{from, 0.0f}};
    using Entry = std::pair<float, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
    open.push({0.0f, from});
    while (!open.empty()) {
        const auto [length, v] = open.top();
        open.pop();
        if (v == to) return true;
        if (length > reached[v]) continue;
        for (int w : features.hardNeighbors[size_t(v)]) {
            const float next = length + glm::length(features.positions[size_t(w)] - features.positions[size_t(v)]);
            if (next > most) continue;
            const auto it = reached.find(w);
            if (it != reached.end() && it->second <= next) continue;
            reached[w] = next;
            open.push({next, w});
        }
    }
    return false;
}

}  // namespace

// What HardEdges keeps, by a name its header can declare.
struct ReferenceFeatures : Features {};

HardEdges::HardEdges(const mesh::PolygonMesh& reference, const FeatureAngles& angles)
    : features_(std::make_shared<const ReferenceFeatures>(ReferenceFeatures{referenceFeatures(reference, angles)})),
      angles_(angles) {}

FeatureCount tagFeatures(mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference, const FeatureAngles& angles) {
    return HardEdges(reference, angles).tag(cage);
}

FeatureCount HardEdges::tag(mesh::PolygonMesh& cage) const {
    const Features& features = *features_;
    const FeatureAngles& angles = angles_;
    std::vector<int> onReference(cage.positions.size(), -1);
    for (size_t v = 0; v < cage.positions.size(); ++v)
        if (const auto it = features.vertexAt.find(cage.positions[v]); it != features.vertexAt.end())
            onReference[v] = it->second;

    FeatureCount count;
    for (const auto& [edge, faces] : edgeFaces(cage)) {
        const int a = onReference[size_t(edge.first)], b = onReference[size_t(edge.second)];
        if (faces.count != 2 || a < 0 || b < 0 || features.hardNeighbors[size_t(a)].empty() ||
            features.hardNeighbors[size_t(b)].empty())
            continue;
        const float length = glm::length(features.positions[size_t(a)] - features.positions[size_t(b)]);
        if (!hardChain(features, a, b, angles.chainDetour * length)) continue;
        cage.tags.creases.push_back({edge.first, edge.second, kInfinitelySharp});
        ++count.creases;
    }
    for (size_t v = 0; v < cage.positions.size(); ++v)
        if (onReference[v] >= 0 && features.corner[size_t(onReference[v])]) {
            cage.tags.corners.push_back({int(v), kInfinitelySharp});
            ++count.corners;
        }
    return count;
}

}  // namespace subdfit::simplify
