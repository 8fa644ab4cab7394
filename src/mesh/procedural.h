#pragma once
// Small generated meshes for tests, benchmarks and the demo: no file, no license question.
#include <cstdint>
#include <functional>

#include "mesh/polygon_mesh.h"

namespace subdfit::mesh {

// A quad-sphere cage: a cube with n×n quads per side projected to the unit sphere
// (6n² quads, eight valence-3 extraordinary vertices). n = 6 gives the ~200-quad cage.
PolygonMesh makeQuadSphere(int n);

// An n×n quad grid over [−1, 1]² in the xy plane (normal +z), z = height(x, y) when given:
// the flat cage of displacement tests, and with a bump function their dense reference.
PolygonMesh makeQuadGrid(int n, const std::function<float(float, float)>& height = {});

// A "lumpy sphere" reference: an icosphere (`subdivisions` levels; 5 → 20 480 triangles)
// with radius 1 + amplitude · Σ of a few smooth random bumps, seeded.
PolygonMesh makeLumpySphere(int subdivisions, float amplitude, std::uint32_t seed);

}  // namespace subdfit::mesh
