#pragma once
// The fitted surface as triangles: the cage's limit surface, displaced along its normal by the
// displacement map, sampled on a regular grid per ptex face. This is what a viewer without
// subdivision or displacement support gets; the normal map then adds the finer detail.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "export/fitted_asset.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::exporter {

struct LimitTessellation {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // unit normals of the displaced surface
    // xyz: unit, orthogonal to the normal, along dP/du; w = ±1 so that cross(normal, xyz) · w
    // points along dP/dv -- the frame the normal map's (x, y) is expressed in.
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec2> uvs;  // atlas texcoords (export/map_atlas.h), glTF convention
    // Pixels of the atlas the uvs address: how much texcoord precision an encoder must keep.
    glm::ivec2 atlasSize{0, 0};
    // Triangles, counter-clockwise seen from outside (the cage's own winding).
    std::vector<std::uint32_t> indices;

    // Only positions and indices are required: a mesh without the others (a cage, a decimated
    // mesh) goes through the same writers.
    bool hasNormals() const { return !normals.empty(); }
    bool hasTangents() const { return !tangents.empty(); }
    bool hasUvs() const { return !uvs.empty(); }
    bool attributesConsistent() const {
        const std::size_t n = positions.size();
        return (!hasNormals() || normals.size() == n) && (!hasTangents() || tangents.size() == n) &&
               (!hasUvs() || uvs.size() == n) && indices.size() % 3 == 0;
    }

    std::size_t vertexCount() const { return positions.size(); }
    std::size_t triangleCount() const { return indices.size() / 3; }
};

// `segments` × `segments` quads per ptex face that has a surface (holes are skipped); each face
// gets its own (segments+1)² vertices, as its texcoords differ from its neighbours'. A multiple
// of maps.layout.resolution puts vertices on every map node. Every output is finite, also
// where the limit derivatives collapse. Throws subdfit::Error for segments outside 1..1024 or
// more than 2³² vertices.
LimitTessellation tessellateLimitSurface(const mesh::PolygonMesh& cage, const FittedMaps& maps, int segments);

}  // namespace subdfit::exporter
