#pragma once
// Midpoint subdivision of a triangle mesh: every triangle into four, the same surface, every
// per-vertex attribute (texture coordinates, colours) interpolated at the new vertices and every
// face keeping its material. Makes a light textured asset dense enough to carry detail finer
// than its triangles (surface/relief_surface.h's addRelief), without touching its appearance.
#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// `triangles`: triangulated, validated. `times` 4-splits (the result has 4^times as many
// triangles). Author normals are dropped (the flat pieces keep the faces' planes; a caller that
// moves vertices recomputes them). An edge's midpoint is shared by the faces that share its two
// vertex indices: a seam (vertices split for their texture coordinates) stays a seam.
PolygonMesh subdividedTriangles(const PolygonMesh& triangles, int times);

}  // namespace subdfit::mesh
