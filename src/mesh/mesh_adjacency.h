#pragma once
// Vertex-to-vertex adjacency of a polygon mesh (e.g. for Laplacian smoothing of a cage).
#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// Compressed rows: the neighbours of vertex v are neighbors[offsets[v] .. offsets[v + 1]),
// sorted ascending and without repeats. offsets has vertexCount() + 1 entries.
struct VertexAdjacency {
    std::vector<int> offsets, neighbors;
};

// Neighbours along face edges. An edge shared by several faces counts once; the self-loops of
// degenerate faces (a vertex repeated in a row) are left out.
VertexAdjacency vertexAdjacency(const PolygonMesh& mesh);

}  // namespace subdfit::mesh
