#pragma once
// The displaced limit surface as triangles, sampled on a regular grid per ptex face: what
// fitted.glb ships (export/ encodes it), what the Chamfer is measured on (geometry/), and the
// smooth reference of synthetic tests (welded).
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "mesh/polygon_mesh.h"
#include "surface/surface_maps.h"

namespace subdfit::surface {

// Where a vertex sits on the surface: a ptex face and (u, v) in it.
struct PtexPoint {
    int face = 0;
    float u = 0.0f, v = 0.0f;
};

struct Tessellation {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // unit normals of the displaced surface
    // The frame of the normal texture the maps carry, as glTF's TANGENT: SurfaceVertex::tangent
    // (along the ptex face's u) for tiles; with an appearance atlas, along its coordinates
    // (surface::atlasTangent).
    std::vector<glm::vec4> tangents;
    std::vector<PtexPoint> ptex;
    std::vector<std::uint32_t> indices;  // counter-clockwise seen from outside (the cage's winding)

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }
};

// `segments` × `segments` quads per ptex face that has a surface (holes are skipped); each face
// gets its own (segments+1)² vertices (their ptex coordinates differ from the neighbours'). A
// multiple of maps.layout.resolution puts vertices on every map node. Every output is finite.
// Throws subdfit::Error for segments outside 1..1024 or more than 2³² vertices.
Tessellation tessellate(const mesh::PolygonMesh& cage, const SurfaceMaps& maps, int segments);

// Triangles (three indices each) as a mesh (positions and faces only).
mesh::PolygonMesh triangleMesh(const std::vector<glm::vec3>& positions, const std::vector<std::uint32_t>& indices);
inline mesh::PolygonMesh triangleMesh(const Tessellation& t) { return triangleMesh(t.positions, t.indices); }

// The same with the vertices that coincide along face borders welded, so that vertexNormals()
// is smooth; triangles collapsed at a pole are dropped.
mesh::PolygonMesh weldedMesh(const Tessellation& tessellation);

// The undisplaced limit surface, welded: the smooth reference of synthetic tests and benchmarks.
mesh::PolygonMesh limitMesh(const mesh::PolygonMesh& cage, int segments);

}  // namespace subdfit::surface
