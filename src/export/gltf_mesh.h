#pragma once
// A triangle mesh with the attributes glTF carries: what the GLB and Draco writers encode. The
// fitted surface comes here from its tessellation (surface/tessellation.h) with atlas texcoords;
// a cage or a decimated mesh with positions and indices alone.
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "codec/map_atlas.h"
#include "surface/tessellation.h"

namespace subdfit::exporter {

struct GltfMesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;  // unit normals of the displaced surface
    // xyz: unit, orthogonal to the normal, along dP/du; w = ±1 so that cross(normal, xyz) · w
    // points along dP/dv -- the frame the normal map's (x, y) is expressed in.
    std::vector<glm::vec4> tangents;
    std::vector<glm::vec2> uvs;  // atlas texcoords (codec/map_atlas.h), glTF convention
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

// The tessellation with each vertex's ptex (face, u, v) turned into texcoords of `atlas`.
GltfMesh gltfMesh(const surface::Tessellation& tessellation, const codec::AtlasLayout& atlas);
// The same, taking the tessellation's positions, normals, tangents and indices instead of
// copying them (a decode's largest arrays); its ptex coordinates stay.
GltfMesh gltfMesh(surface::Tessellation&& tessellation, const codec::AtlasLayout& atlas);

}  // namespace subdfit::exporter
