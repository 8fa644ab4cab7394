#pragma once
// A quad-dominant remesh of a triangle mesh, its edges following a smooth cross field and its
// vertices about evenly spaced: what a subdivision cage wants (Catmull-Clark is at its best on
// quads whose vertices have four neighbours), where decimation leaves triangles, every one of
// which Catmull-Clark splits around an extraordinary vertex. The method is Instant Meshes'
// (Jakob, Tarini, Panozzo, Sorkine-Hornung 2015): surfaceHierarchy, orientationField,
// positionField, then extractQuads.
#include <glm/vec3.hpp>
#include <vector>

#include "mesh/polygon_mesh.h"
#include "simplify/remesh/cross_field.h"

namespace subdfit::simplify::remesh {

struct QuadRemeshOptions {
    int vertices = 1000;  // about how many the remesh has
    FieldSweeps sweeps{};
};

struct QuadRemesh {
    mesh::PolygonMesh mesh;          // quads, a few triangles and small polygons
    std::vector<glm::vec3> normals;  // per vertex, the input's there
    float edgeLength = 0.0f;         // asked of the quads
    double quadShare() const;        // of the faces
};

// `triangles`: welded, any density (long edges are split first). Throws subdfit::Error naming
// its file where the result is not a manifold polygon mesh (a part thinner than the quads, say).
QuadRemesh quadRemesh(const mesh::PolygonMesh& triangles, const QuadRemeshOptions& options);

}  // namespace subdfit::simplify::remesh
