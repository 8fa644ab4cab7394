#pragma once
// A dense reference with a clear license, made rather than downloaded: the limit surface of a
// cage (e.g. the bundled CC0 Spot) tessellated finely, with a procedural relief along its
// normals, like a sculpted asset: a smooth base and fine detail. What `simplify` is for, and
// what README command 1 and `subdfit-bench simplify` run on.
#include <cstdint>

#include "mesh/polygon_mesh.h"

namespace subdfit::surface {

struct ReliefOptions {
    int segments = 24;                                            // per cage-face edge
    float amplitude = 0.004f;                                     // RMS height, a fraction of the bounding-box diagonal
    float shortestWavelength = 0.02f, longestWavelength = 0.06f;  // same units
    int waves = 16;                                               // plane waves summed, random directions and phases
    std::uint32_t seed = 1;
    // The share of the surface the relief covers: 1 everywhere; below it, patches where a field
    // of long waves passes its quantile, fading over a short margin (a sculpt's detail lies where
    // the artist put it, the rest of the base left smooth).
    float coverage = 1.0f;
};

// Moves every vertex of `surface` along its normal by the relief's height there (the options'
// wavelengths and amplitude are fractions of its bounding-box diagonal). Vertices at one position
// (a texture seam) move together; texture coordinates, colours and materials stay as they are,
// and `normals` become the relieved surface's, alike on both sides of a seam.
void addRelief(mesh::PolygonMesh& surface, const ReliefOptions& options);

// Welded triangles, in the cage's units. Deterministic for a given cage and options.
mesh::PolygonMesh reliefSurface(const mesh::PolygonMesh& cage, const ReliefOptions& options = {});

}  // namespace subdfit::surface
