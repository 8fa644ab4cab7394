#pragma once
// Plain decimation with meshoptimizer's quadric edge collapse: the starting point of
// `simplify`'s cage, and the baseline that cage is judged against.
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

// The triangles of `mesh` with coincident positions merged into one vertex (a glTF asset splits
// vertices at UV and normal seams; a cage must not have cracks there). Degenerate triangles
// and unused vertices are dropped.
mesh::PolygonMesh weldedTriangles(const mesh::PolygonMesh& mesh);

// `triangles` (welded) collapsed to at most `targetTriangles`, preserving topology where
// meshoptimizer can; only when topology-preserving collapse gets stuck far above the target
// (many small components, say) does it fall back to the sloppy clustering simplifier. Never
// returns an empty mesh for a non-empty input. Throws subdfit::Error for targetTriangles < 1.
mesh::PolygonMesh decimate(const mesh::PolygonMesh& triangles, int targetTriangles);

// `triangles` (welded) clustered to at most `targetTriangles` by meshoptimizer's sloppy
// simplifier alone: vertices merged cell by cell, components and holes free to merge, so any
// count is reached on any input (scans, CAD soups) where edge collapse may stall. Its vertices
// are a subset of the input's. Throws as decimate does.
mesh::PolygonMesh cluster(const mesh::PolygonMesh& triangles, int targetTriangles);

}  // namespace subdfit::simplify
