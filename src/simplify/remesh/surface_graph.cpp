#include "simplify/remesh/surface_graph.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "mesh/mesh_adjacency.h"

namespace subdfit::simplify::remesh {
namespace {

GraphLevel finestLevel(const mesh::PolygonMesh& triangles) {
    GraphLevel level;
    level.positions = triangles.positions;
    level.normals.assign(triangles.positions.size(), glm::vec3(0.0f));
    level.areas.assign(triangles.positions.size(), 0.0f);
    for (int f = 0; f < triangles.faceCount(); ++f) {
        const int* v = &triangles.faceIndices[size_t(3 * f)];
        const glm::vec3 n = glm::cross(triangles.positions[size_t(v[1])] - triangles.positions[size_t(v[0])],
                                       triangles.positions[size_t(v[2])] - triangles.positions[size_t(v[0])]);
        for (int k = 0; k < 3; ++k) {
            level.normals[size_t(v[k])] += n;
            level.areas[size_t(v[k])] += glm::length(n) / 6.0f;
        }
    }
    for (glm::vec3& n : level.normals) {
        const float length = glm::length(n);
        n = length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
    }
    mesh::VertexAdjacency adjacency = mesh::vertexAdjacency(triangles);
    level.offsets = std::move(adjacency.offsets);
    level.neighbors = std::move(adjacency.neighbors);
    level.weights.assign(level.neighbors.size(), 1.0f);
    return level;
}

// Greedy matching, best-aligned pairs first: merging samples whose normals agree keeps each
// coarse sample's tangent plane meaningful.
GraphLevel coarser(GraphLevel& fine) {
    struct Pair {
        float score;
        int a, b;
    };
    std::vector<Pair> pairs;
    for (int a = 0; a < fine.size(); ++a)
        for (int k = fine.offsets[size_t(a)]; k < fine.offsets[size_t(a) + 1]; ++k) {
            const int b = fine.neighbors[size_t(k)];
            if (a < b) pairs.push_back({glm::dot(fine.normals[size_t(a)], fine.normals[size_t(b)]), a, b});
        }
    std::stable_sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) { return x.score > y.score; });
    fine.parent.assign(size_t(fine.size()), -1);
    GraphLevel coarse;
    auto addParent = [&](int a, int b) {
        const int p = coarse.size();
        const float area = fine.areas[size_t(a)] + (b >= 0 ? fine.areas[size_t(b)] : 0.0f);
        glm::vec3 position = fine.positions[size_t(a)], normal = fine.normals[size_t(a)];
        if (b >= 0) {
            const float wa = area > 0.0f ? fine.areas[size_t(a)] / area : 0.5f;
            position = wa * position + (1.0f - wa) * fine.positions[size_t(b)];
            const glm::vec3 sum = fine.areas[size_t(a)] * normal + fine.areas[size_t(b)] * fine.normals[size_t(b)];
            if (glm::length(sum) > 0.0f) normal = glm::normalize(sum);
            fine.parent[size_t(b)] = p;
        }
        fine.parent[size_t(a)] = p;
        coarse.positions.push_back(position);
        coarse.normals.push_back(normal);
        coarse.areas.push_back(area);
        const float wa = b < 0 || !(area > 0.0f) ? 1.0f : fine.areas[size_t(a)] / area;
        coarse.scales.push_back(wa * fine.scales[size_t(a)] + (b < 0 ? 0.0f : (1.0f - wa) * fine.scales[size_t(b)]));
    };
    for (const Pair& pair : pairs)
        if (fine.parent[size_t(pair.a)] < 0 && fine.parent[size_t(pair.b)] < 0) addParent(pair.a, pair.b);
    for (int a = 0; a < fine.size(); ++a)
        if (fine.parent[size_t(a)] < 0) addParent(a, -1);

    // The coarse edges: the fine edges between different parents, their weights summed.
    struct Edge {
        int a, b;
        float weight;
    };
    std::vector<Edge> edges;
    for (int a = 0; a < fine.size(); ++a)
        for (int k = fine.offsets[size_t(a)]; k < fine.offsets[size_t(a) + 1]; ++k) {
            const int pa = fine.parent[size_t(a)], pb = fine.parent[size_t(fine.neighbors[size_t(k)])];
            if (pa != pb) edges.push_back({pa, pb, fine.weights[size_t(k)]});
        }
    std::sort(edges.begin(), edges.end(),
              [](const Edge& x, const Edge& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
    coarse.offsets.assign(size_t(coarse.size()) + 1, 0);
    for (size_t e = 0; e < edges.size(); ++e) {
        if (e > 0 && edges[e].a == edges[e - 1].a && edges[e].b == edges[e - 1].b) {
            coarse.weights.back() += edges[e].weight;
            continue;
        }
        coarse.neighbors.push_back(edges[e].b);
        coarse.weights.push_back(edges[e].weight);
        ++coarse.offsets[size_t(edges[e].a) + 1];
    }
    std::partial_sum(coarse.offsets.begin(), coarse.offsets.end(), coarse.offsets.begin());
    return coarse;
}

// Greedy colouring in sample order.
std::vector<std::vector<int>> independentSets(const GraphLevel& level) {
    std::vector<int> color(size_t(level.size()), -1);
    std::vector<std::vector<int>> sets;
    std::vector<char> taken;
    for (int v = 0; v < level.size(); ++v) {
        taken.assign(sets.size() + 1, 0);
        for (int k = level.offsets[size_t(v)]; k < level.offsets[size_t(v) + 1]; ++k) {
            const int c = color[size_t(level.neighbors[size_t(k)])];
            if (c >= 0) taken[size_t(c)] = 1;
        }
        int c = 0;
        while (taken[size_t(c)]) ++c;
        if (size_t(c) == sets.size()) sets.emplace_back();
        sets[size_t(c)].push_back(v);
        color[size_t(v)] = c;
    }
    return sets;
}

}  // namespace

std::vector<GraphLevel> surfaceHierarchy(const mesh::PolygonMesh& triangles, std::vector<float> scales, int coarsest) {
    std::vector<GraphLevel> levels;
    levels.push_back(finestLevel(triangles));
    levels[0].scales = std::move(scales);
    while (levels.back().size() > coarsest) {
        GraphLevel next = coarser(levels.back());
        if (next.size() * 10 > levels.back().size() * 9) {  // stalled: little is left to match
            levels.back().parent.clear();
            break;
        }
        levels.push_back(std::move(next));
    }
    for (GraphLevel& level : levels) level.independentSets = independentSets(level);
    return levels;
}

}  // namespace subdfit::simplify::remesh
