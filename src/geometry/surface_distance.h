#pragma once
// Geometric error between two triangle meshes: area-uniform samples on each, exact distance to
// the nearest point of the other (Embree point queries, geometry/surface_queries.h).
#include <cstdint>

#include "mesh/polygon_mesh.h"

namespace subdfit::geometry {

struct SurfaceDistance {
    double chamferL2Squared = 0.0;  // mean d²(A→B) + mean d²(B→A)
    double meanDistance = 0.0;      // mean of d over both directions' samples
    double hausdorff = 0.0;         // max over both directions
};

class SurfaceQueries;

// Both meshes triangulated. `samples` points per side, seeded.
SurfaceDistance surfaceDistance(const mesh::PolygonMesh& a, const mesh::PolygonMesh& b, int samples = 100000,
                                std::uint32_t seed = 7);

// The same against `b`'s queries, built once by a caller that measures many meshes against one.
SurfaceDistance surfaceDistance(const mesh::PolygonMesh& a, const SurfaceQueries& b, int samples = 100000,
                                std::uint32_t seed = 7);

}  // namespace subdfit::geometry
