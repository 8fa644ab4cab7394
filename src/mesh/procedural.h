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
// with radius 1 + amplitude · Σ_k h_k exp(−(1 − d·c_k) / w_k) over `bumps` random bumps of
// width w_k in [minWidth, maxWidth] (in 1 − cos units: w = 0.005 is ~0.1 rad across), seeded.
PolygonMesh makeLumpySphere(int subdivisions, float amplitude, std::uint32_t seed, int bumps = 12,
                            float minWidth = 0.05f, float maxWidth = 0.2f);

}  // namespace subdfit::mesh
