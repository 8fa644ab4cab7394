#include "mesh/mesh_geometry.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "mesh/position_map.h"
#include "util/error.h"

namespace subdfit::mesh {
namespace {

// `v` made unit; +Z where it has no length (opposite faces can cancel exactly, a face can have
// no area): any unit vector is then as good as another, and never NaN.
glm::vec3 unitOrUp(const glm::dvec3& v) {
    const double length = glm::length(v);
    return length > 0.0 && std::isfinite(length) ? glm::vec3(v / length) : glm::vec3(0, 0, 1);
}

}  // namespace

PolygonMesh triangulated(const PolygonMesh& mesh) {
    PolygonMesh out;
    out.positions = mesh.positions;
    out.sourcePath = mesh.sourcePath;
    out.uvs = mesh.uvs;
    out.colors = mesh.colors;
    out.normals = mesh.normals;
    out.materials = mesh.materials;
    std::vector<char> isHole(mesh.faceSizes.size(), 0);
    for (int f : mesh.tags.holes)
        if (f >= 0 && f < mesh.faceCount()) isHole[size_t(f)] = 1;

    size_t first = 0;
    for (size_t f = 0; f < mesh.faceSizes.size(); first += size_t(mesh.faceSizes[f]), ++f) {
        if (isHole[f]) continue;
        const int* v = mesh.faceIndices.data() + first;
        for (int k = 1; k + 1 < mesh.faceSizes[f]; ++k) {
            SUBDFIT_CHECK(first + size_t(k) + 1 < mesh.faceIndices.size());
            out.faceIndices.insert(out.faceIndices.end(), {v[0], v[k], v[k + 1]});
            out.faceSizes.push_back(3);
            if (!mesh.faceMaterials.empty()) out.faceMaterials.push_back(mesh.faceMaterials[f]);
        }
    }
    return out;
}

std::vector<glm::vec3> vertexNormals(const PolygonMesh& mesh) {
    // Doubles, so that neither tiny nor huge coordinates underflow or overflow in the cross
    // products of a float-range mesh.
    std::vector<glm::dvec3> sums(mesh.positions.size(), glm::dvec3(0.0));
    size_t first = 0;
    for (size_t f = 0; f < mesh.faceSizes.size(); first += size_t(mesh.faceSizes[f]), ++f) {
        const int n = mesh.faceSizes[f];
        const int* v = mesh.faceIndices.data() + first;
        for (int k = 0; k < n; ++k) SUBDFIT_CHECK(v[k] >= 0 && v[k] < mesh.vertexCount());
        // Newell's vector area (twice the area, along the normal; also for non-planar
        // polygons), taken about the first corner so that a small face far from the origin
        // does not lose its area to cancellation.
        const glm::dvec3 origin(mesh.positions[size_t(v[0])]);
        glm::dvec3 area(0.0);
        for (int k = 1; k + 1 < n; ++k)
            area += glm::cross(glm::dvec3(mesh.positions[size_t(v[k])]) - origin,
                               glm::dvec3(mesh.positions[size_t(v[k + 1])]) - origin);
        if (!std::isfinite(area.x) || !std::isfinite(area.y) || !std::isfinite(area.z)) continue;
        for (int k = 0; k < n; ++k) sums[size_t(v[k])] += area;
    }

    std::vector<glm::vec3> normals(sums.size());
    for (size_t i = 0; i < sums.size(); ++i) normals[i] = unitOrUp(sums[i]);
    return normals;
}

PolygonMesh flatShaded(const PolygonMesh& triangles) {
    PolygonMesh out;
    out.sourcePath = triangles.sourcePath;
    out.materials = triangles.materials;
    out.faceMaterials = triangles.faceMaterials;
    out.faceSizes = triangles.faceSizes;
    const size_t corners = triangles.faceIndices.size();
    out.positions.reserve(corners);
    out.normals.reserve(corners);
    for (size_t f = 0; f < triangles.faceSizes.size(); ++f) {
        SUBDFIT_CHECK(triangles.faceSizes[f] == 3);
        const int* v = triangles.faceIndices.data() + 3 * f;
        const glm::dvec3 a(triangles.positions[size_t(v[0])]), b(triangles.positions[size_t(v[1])]),
            c(triangles.positions[size_t(v[2])]);
        const glm::vec3 normal = unitOrUp(glm::cross(b - a, c - a));
        for (int k = 0; k < 3; ++k) {
            const auto corner = size_t(v[k]);
            out.faceIndices.push_back(int(out.positions.size()));
            out.positions.push_back(triangles.positions[corner]);
            out.normals.push_back(normal);
            if (!triangles.uvs.empty()) out.uvs.push_back(triangles.uvs[corner]);
            if (!triangles.colors.empty()) out.colors.push_back(triangles.colors[corner]);
        }
    }
    return out;
}

std::vector<glm::vec3> shadingNormals(const PolygonMesh& mesh) {
    return mesh.normals.empty() ? vertexNormals(mesh) : mesh.normals;
}

bool oneNormalPerPosition(const PolygonMesh& mesh) {
    const std::vector<glm::vec3> normals = shadingNormals(mesh);
    PositionMap<size_t> first;
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
        const auto [it, fresh] = first.try_emplace(mesh.positions[v], v);
        if (!fresh && glm::dot(normals[v], normals[it->second]) < 0.9999f) return false;
    }
    return true;
}

bool hasNonQuadFaces(const PolygonMesh& m) {
    return std::any_of(m.faceSizes.begin(), m.faceSizes.end(), [](int n) { return n != 4; });
}

int quadCount(const PolygonMesh& m) { return int(std::count(m.faceSizes.begin(), m.faceSizes.end(), 4)); }

float meanEdgeLength(const PolygonMesh& m) {
    double total = 0.0;
    size_t edges = 0;
    size_t first = 0;
    for (int size : m.faceSizes) {
        for (int k = 0; k < size; ++k, ++edges)
            total += glm::length(m.positions[size_t(m.faceIndices[first + size_t(k)])] -
                                 m.positions[size_t(m.faceIndices[first + size_t((k + 1) % size)])]);
        first += size_t(size);
    }
    return edges ? float(total / double(edges)) : 0.0f;
}

}  // namespace subdfit::mesh
