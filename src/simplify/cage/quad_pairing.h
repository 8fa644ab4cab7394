#pragma once
// A triangle cage made quad-dominant by joining pairs of triangles across their shared edge.
// Under Catmull-Clark a triangle is three quads around an extraordinary vertex, so a cage of
// triangles has no regular patch; two triangles joined are one quad, and where a decimated mesh's
// vertices have about six neighbours a paired one's have about four. The pairs are chosen
// greedily, best quads first: a pair is a candidate when its quad is convex and not folded (its
// corners' angles below kMostCornerDegrees, its triangles within kMostFoldDegrees of each other)
// and their edge is no crease; the score prefers right angles and flat pairs. Vertices, creases
// and corners stay as they are.
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

struct QuadPairing {
    float mostCornerDegrees = 150.0f;
    float mostFoldDegrees = 40.0f;
};

// `triangles`: all faces triangles, no holes. The quads keep the triangles' orientation; the
// triangles left unpaired follow the quads, in their order.
mesh::PolygonMesh pairIntoQuads(const mesh::PolygonMesh& triangles, const QuadPairing& pairing = {});

}  // namespace subdfit::simplify
