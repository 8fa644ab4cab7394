#pragma once
// One uniform Catmull-Clark step of a cage: all quads (an n-gon becomes n), the same limit
// surface. A tessellation of it samples every face alike, where an n-gon's per-corner ptex
// tiles would be sampled twice as finely as a neighbouring quad's (T-junctions).
#include <glm/vec2.hpp>

#include <vector>

#include "mesh/polygon_mesh.h"

namespace subdfit::subdiv {

// Creases and corners carry over with their refined sharpness, holes with their children; the
// rules (boundary, crease method, triangles) are the cage's. Sharpness that the boundary rule
// implies (boundary edges, and with edge-and-corner the corners of one face) is not tagged.
mesh::PolygonMesh refinedOnce(const mesh::PolygonMesh& cage);

// The refined cage, and where each of its faces lies on the cage's ptex faces: every child face
// is inside one ptex face (a quad's child is a quarter of it, an n-gon's child is one of its n
// ptex faces), and its four corners sit at these (u, v) there, in the child's corner order. The
// child's own (u, v) is the bilinear blend of them: the limit surface, tiles and atlas
// coordinates all map exactly.
struct RefinedCage {
    mesh::PolygonMesh mesh;
    std::vector<int> ptexFace;        // per face of mesh
    std::vector<glm::vec2> cornerUv;  // 4 per face of mesh
};
RefinedCage refinedOnceWithPtex(const mesh::PolygonMesh& cage);

}  // namespace subdfit::subdiv
