#pragma once
// A decimated triangle cage made quad-dominant by joining pairs of neighbouring triangles across
// their shared edge, as "tris to quads" in a DCC does: the vertices stay where decimation put
// them (denser where the surface bends), and each joined pair drops an edge, so the mean valence
// goes from about six towards four, the regular valence of Catmull-Clark.
#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

struct TrianglePairingOptions {
    // A pair is joined only when every corner of its quad lies within this many degrees of a right
    // angle (a quad close to a triangle makes a pinched patch) and the two triangles' normals
    // within `mostFold` degrees of each other.
    float mostCornerSkew = 80.0f;
    float mostFold = 60.0f;
};

// `triangles` (faces of three corners, creases by vertex pair) with the best-shaped pairs
// joined, best first, each triangle at most once; creased edges, boundaries, edges of more than
// two faces and pairs of opposite winding are never joined. Faces keep the order of their first
// triangle; tags and holes follow them.
mesh::PolygonMesh pairTriangles(const mesh::PolygonMesh& triangles, const TrianglePairingOptions& options = {});

}  // namespace subdfit::simplify
