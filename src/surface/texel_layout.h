#pragma once
// Where the texels of the displacement and normal maps live. Every ptex face of the cage gets a
// tile of T×T cells whose (T+1)² corner nodes carry the values; a map is sampled bilinearly
// from the nodes. Nodes on a tile's border are *shared* with the neighbouring tiles (welded by
// their limit position), so a map is continuous across faces: no seams, and a displaced
// surface stays watertight wherever the limit normal is continuous.
#include <glm/vec2.hpp>

#include <span>
#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::surface {

struct TexelLayout {
    int resolution = 0;  // T: cells per ptex-face edge
    int ptexFaceCount = 0;
    int nodeCount = 0;           // distinct parameters per channel
    std::vector<int> faceNodes;  // [face][j][i] -> node, i along u, j along v, (T+1)² per face
    // The ring of nodes just outside each tile, in the tile's own (i, j): [face][edge][k] -> the
    // neighbouring tile's node one row in from the shared edge, or -1 where there is none (a
    // boundary, a hole, a non-manifold edge). Edges: 0 at j = 0, 1 at i = T, 2 at j = T, 3 at
    // i = 0; k runs along increasing i or j. It lets a slope near a face edge be a central
    // difference, so both faces agree on it (shading without a kink at every cage edge).
    std::vector<int> halo;

    int nodesPerFace() const { return (resolution + 1) * (resolution + 1); }
    int node(int face, int i, int j) const {
        return faceNodes[size_t(face) * size_t(nodesPerFace()) + size_t(j) * size_t(resolution + 1) + size_t(i)];
    }
};

// The node graph: grid neighbours within every tile, so nodes on shared borders gather the
// neighbours of all their tiles (CSR, unique). The maps' smoothing preconditioner runs on it.
struct NodeAdjacency {
    std::vector<int> offsets, neighbors;
};
NodeAdjacency nodeAdjacency(const TexelLayout& layout);

// `resolution` in 1..256 (the options allow up to 64). The layouts of the last few cages are
// kept: laying one out again costs a comparison.
TexelLayout buildTexelLayout(const mesh::PolygonMesh& cage, int resolution);

// Bilinear sample of channel `channel` of node values stored `stride` floats per node, at ptex
// (u, v) of `face` ((u, v) is clamped to the tile: rasterised (u, v) can stray by ~1e-3).
float sampleBilinear(const TexelLayout& layout, std::span<const float> values, int stride, int channel, int face,
                     float u, float v);

// The value at node (i, j) of `face`'s tile, where one of i, j may lie one step outside it
// (-1 or T + 1): the neighbouring tile's node across that edge, or without a neighbour the
// border cell's slope extended (2·border − inner). glsl/surface_point.glsl does exactly the same.
float nodeValueAcross(const TexelLayout& layout, std::span<const float> values, int face, int i, int j);

// (∂/∂u, ∂/∂v) of a one-value-per-node map at ptex (u, v) of `face` by central differences half
// a cell wide, reaching into the neighbouring tiles near the border (nodeValueAcross): at a
// node it averages the slopes of the cells on either side, whichever tile they are in.
glm::vec2 slopeAcrossTiles(const TexelLayout& layout, std::span<const float> values, int face, float u, float v);

}  // namespace subdfit::surface
