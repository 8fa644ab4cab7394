#pragma once
// A triangle mesh as a graph of surface samples, and coarser copies of it: what the fields of a
// field-aligned remesher (Jakob et al., Instant Field-Aligned Meshes, 2015) are smoothed on. A
// field smoothed on the fine graph alone needs as many sweeps as the graph is wide to lose its
// local twists; smoothed coarse to fine it needs a few per level.
#include <glm/vec3.hpp>
#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::simplify::remesh {

struct GraphLevel {
    std::vector<glm::vec3> positions, normals;  // unit normals
    std::vector<float> areas;                   // the surface each sample stands for
    std::vector<float> scales;                  // the quads' edge length wanted there
    std::vector<int> offsets, neighbors;        // compressed rows, as mesh::VertexAdjacency
    std::vector<float> weights;                 // one per neighbors entry
    std::vector<int> parent;                    // the sample of the next coarser level (none on the coarsest)
    // The samples in groups of which no two are neighbours: a sweep over one group can run on
    // every core and still do what a sweep in order does.
    std::vector<std::vector<int>> independentSets;

    int size() const { return int(positions.size()); }
};

// Level 0 is `triangles`' vertices and edges, with `scales` (one per vertex); each next level
// merges matched pairs of neighbours (about half as many samples, their mean scale) until at
// most `coarsest` are left or merging stalls.
std::vector<GraphLevel> surfaceHierarchy(const mesh::PolygonMesh& triangles, std::vector<float> scales,
                                         int coarsest = 64);

}  // namespace subdfit::simplify::remesh
