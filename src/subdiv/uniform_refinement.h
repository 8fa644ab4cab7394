#pragma once
// One uniform Catmull-Clark step of a cage: all quads (an n-gon becomes n), the same limit
// surface. A tessellation of it samples every face alike, where an n-gon's per-corner ptex
// tiles would be sampled twice as finely as a neighbouring quad's (T-junctions).
#include "mesh/polygon_mesh.h"

namespace subdfit::subdiv {

// Creases and corners carry over with their refined sharpness, holes with their children; the
// rules (boundary, crease method, triangles) are the cage's.
mesh::PolygonMesh refinedOnce(const mesh::PolygonMesh& cage);

}  // namespace subdfit::subdiv
