#pragma once
// The hard edges of a reference, carried onto its decimated cage as OpenSubdiv tags. A
// Catmull-Clark surface rounds every edge of its cage: a box comes out a pillow, a plate's rim a
// bead. A cage edge that follows a chain of the reference's hard edges becomes an infinitely
// sharp crease (OpenSubdiv makes a vertex where three or more meet a corner), and a boundary
// vertex where the reference's boundary turns sharply becomes a corner. A hard edge is one the
// reference is *shaded* hard along: its vertices are split there (as a box's, or any asset's
// with flat-shaded parts) and the shading normals of the two sides part by more than a set
// angle. The reference decides, not the cage (a coarse cage over a smooth part turns sharply at
// its edges too), and its own shading, not its facets (a 4 K-triangle duck meets at 50° along
// its beak, and is shaded smooth there).
#include <memory>

#include "mesh/polygon_mesh.h"

namespace subdfit::simplify {

struct FeatureAngles {
    float edgeDegrees = 45.0f;      // a reference edge is hard when its two sides' normals part by more
    float boundaryDegrees = 75.0f;  // a reference boundary turning by more at a vertex makes a corner
    // How much longer than the cage edge the chain of hard edges under it may be.
    float chainDetour = 1.25f;
};

struct FeatureCount {
    int creases = 0, corners = 0;
};

// Adds the creases and corners to `cage.tags`. `reference`: triangles as read (vertices split
// where the file splits them), shaded with mesh::shadingNormals as the reference renderer does.
// `cage`: triangles whose vertices lie at vertices of `reference`, as decimation leaves them; a
// cage vertex found nowhere on it takes part in no feature.
FeatureCount tagFeatures(mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference, const FeatureAngles& angles = {});

struct ReferenceFeatures;

// The same, with the reference's hard edges and corners found once for the cages of any number
// of face counts (the budget search's).
class HardEdges {
public:
    explicit HardEdges(const mesh::PolygonMesh& reference, const FeatureAngles& angles = {});
    FeatureCount tag(mesh::PolygonMesh& cage) const;

private:
    std::shared_ptr<const ReferenceFeatures> features_;
    FeatureAngles angles_;
};

}  // namespace subdfit::simplify
