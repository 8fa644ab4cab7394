#include "surface/tessellation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "mesh/point_welder.h"
#include "surface/appearance_atlas.h"
#include "surface/displaced_surface.h"
#include "util/error.h"

namespace subdfit::surface {

Tessellation tessellate(const mesh::PolygonMesh& cage, const SurfaceMaps& maps, int segments) {
    if (segments < 1 || segments > 1024)
        throw Error("tessellation segments must be in 1..1024, got " + std::to_string(segments));
    const DisplacedSurface surface(cage, maps);

    std::vector<int> faces;
    for (int face = 0; face < surface.ptexFaceCount(); ++face)
        if (surface.hasSurface(face)) faces.push_back(face);
    const size_t side = size_t(segments) + 1;
    const size_t vertexCount = faces.size() * side * side;
    if (vertexCount > size_t(std::numeric_limits<std::uint32_t>::max()))
        throw Error(std::to_string(segments) + " tessellation segments give " + std::to_string(vertexCount) +
                    " vertices, more than 32-bit indices address");

    Tessellation out;
    out.positions.reserve(vertexCount);
    out.normals.reserve(vertexCount);
    out.tangents.reserve(vertexCount);
    out.ptex.reserve(vertexCount);
    out.indices.reserve(faces.size() * size_t(segments) * size_t(segments) * 6);
    for (int face : faces) {
        const auto base = std::uint32_t(out.positions.size());
        for (int j = 0; j <= segments; ++j)
            for (int i = 0; i <= segments; ++i) {
                const float u = float(i) / float(segments), v = float(j) / float(segments);
                const SurfaceVertex vertex = surface.at(face, u, v);
                out.positions.push_back(vertex.position);
                out.normals.push_back(vertex.normal);
                out.tangents.push_back(maps.appearanceAtlas.present()
                                           ? atlasTangent(vertex.normal, vertex.dPdu, vertex.dPdv,
                                                          atlasUvJacobian(maps.appearanceAtlas, face, u, v),
                                                          vertex.tangent)
                                           : vertex.tangent);
                out.ptex.push_back({face, u, v});
            }
        // (u, v) → (u+1, v) → (u+1, v+1) turns counter-clockwise about dP/du × dP/dv, which
        // OpenSubdiv orients like the cage face: outwards for a cage wound CCW from outside.
        for (int j = 0; j < segments; ++j)
            for (int i = 0; i < segments; ++i) {
                const std::uint32_t a = base + std::uint32_t(size_t(j) * side + size_t(i)), b = a + 1,
                                    d = a + std::uint32_t(side), c = d + 1;
                out.indices.insert(out.indices.end(), {a, b, c, a, c, d});
            }
    }
    return out;
}

mesh::PolygonMesh triangleMesh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices) {
    mesh::PolygonMesh mesh;
    mesh.positions = positions;
    mesh.faceSizes.assign(indices.size() / 3, 3);
    mesh.faceIndices.assign(indices.begin(), indices.end());
    return mesh;
}

mesh::PolygonMesh weldedMesh(const Tessellation& t) {
    float extent = 0.0f;
    for (const auto& p : t.positions) extent = std::max({extent, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    // Far finer than the samples, far coarser than float rounding of one limit point.
    mesh::PointWelder welder(std::max(extent, 1e-30f) * 1e-6f);
    mesh::PolygonMesh mesh;
    std::vector<int> index(t.positions.size());
    int next = 0;
    for (size_t v = 0; v < t.positions.size(); ++v) {
        index[v] = welder.indexOf(t.positions[v], next);
        if (index[v] == mesh.vertexCount()) mesh.positions.push_back(t.positions[v]);
    }
    for (size_t k = 0; k < t.indices.size(); k += 3) {
        const std::array<int, 3> tri = {index[t.indices[k]], index[t.indices[k + 1]], index[t.indices[k + 2]]};
        if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;  // collapsed at a pole
        mesh.faceSizes.push_back(3);
        mesh.faceIndices.insert(mesh.faceIndices.end(), tri.begin(), tri.end());
    }
    return mesh;
}

mesh::PolygonMesh limitMesh(const mesh::PolygonMesh& cage, int segments) {
    mesh::PolygonMesh mesh = weldedMesh(tessellate(cage, {}, segments));
    mesh.sourcePath = cage.sourcePath + " (limit surface)";
    return mesh;
}

}  // namespace subdfit::surface
