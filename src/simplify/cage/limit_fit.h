#pragma once
// A cage moved so that its limit surface lies on a reference surface in the least-squares
// sense, over whole faces rather than at the vertices only. Interpolating the vertices (the
// initial cage's first step) makes an approximating scheme overshoot between them: a dense
// triangle cage comes out rippled, its shading wrinkled, and every map baked onto it pays for
// the ripples. Fitting samples across each face removes them.
//
// Each round samples the limit surface on a grid per ptex face, casts each sample along its
// limit normal to the reference (the hit is where that sample should be), and solves the damped
// normal equations (LᵀL + μI) ΔP = Lᵀ(t − LP) by preconditioned conjugate gradients: L holds the
// limit stencils of the samples over the cage vertices, so the surface, linear in P, moves
// towards the hits in one solve. Samples whose ray finds no reference nearby pull nothing.
#include "geometry/surface_queries.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

struct LimitFitOptions {
    int rounds = 4;            // project + solve; the hits move as the surface does
    int samplesPerEdge = 3;    // a samplesPerEdge² grid inside each ptex face
    double damping = 0.02;     // μ as a fraction of the normal matrix's mean diagonal
    float reach = 1.0f;        // rays reach this many mean cage edge lengths
    float detour = 0.25f;      // a hit farther than the nearest point by more of the reach is another part's
    bool measureAfter = true;  // cast every sample once more for the report's rmsAfter (a fifth of the rays)
};

struct LimitFitReport {
    double rmsBefore = 0.0, rmsAfter = 0.0;  // over the samples that found the reference (after: 0 unless measured)
    int samples = 0, hits = 0;
};

// `referenceTriangles`: triangles in the cage's units. Positions of `cage` are replaced; its
// topology is kept. Vertices no sample sees stay where they are.
LimitFitReport fitLimitToSurface(mesh::PolygonMesh& cage, const mesh::PolygonMesh& referenceTriangles,
                                 const LimitFitOptions& options = {});
// The same on a reference whose ray queries are built already (`surface`, of referenceTriangles).
LimitFitReport fitLimitToSurface(mesh::PolygonMesh& cage, const mesh::PolygonMesh& referenceTriangles,
                                 const geometry::SurfaceQueries& surface, const LimitFitOptions& options = {});

}  // namespace subdfit::simplify
