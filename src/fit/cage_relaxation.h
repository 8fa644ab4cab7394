#pragma once
// Keeps a cage clean while the images move it. The images constrain a control vertex along the
// limit surface's normal; along the surface they barely see it, so noise there (a noised start,
// SGE's own noise) stays or grows while the surface improves. Each step, every vertex slides a
// fraction of the way towards the centroid of its neighbours *within its tangent plane*: the
// cage relaxes in its own sense without changing the shape the images fitted. Creases are
// respected: a vertex on a crease chain slides along the chain towards its two crease
// neighbours, and a corner (a corner tag, an end of a chain, where chains meet) stays put.
// Boundaries count as creases, as OpenSubdiv's edge-only boundary rule treats them.
#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "mesh/polygon_mesh.h"

namespace subdfit::fit {

// How each vertex may move, and what it averages (CPU, for the GPU pass and for tests).
struct RelaxationTopology {
    enum Mode : int { Surface = 0, Crease = 1, Fixed = 2 };
    std::vector<int> modes;                  // per vertex
    std::vector<int> offsets, neighbors;     // CSR: the vertices each one averages
    std::vector<int> cornerOffsets, corners;  // CSR of (previous, next) pairs: the face corners at a vertex
};
RelaxationTopology relaxationTopology(const mesh::PolygonMesh& cage);

class CageRelaxation {
public:
    explicit CageRelaxation(const mesh::PolygonMesh& cage);

    // θ += rate · (tangential move towards the neighbours' centroid), every vertex at once.
    void apply(gl::ProgramCache& programs, gl::Buffer& theta, float rate);
    // gradient −= (1 − keep) · (its tangential part at θ), in place.
    void projectGradient(gl::ProgramCache& programs, const gl::Buffer& theta, gl::Buffer& gradient, float keep);

private:
    void dispatchOverVertices();  // binds the topology, one thread per vertex

    int vertexCount_;
    gl::Buffer modes_, offsets_, neighbors_, cornerOffsets_, corners_, scratch_;
};

}  // namespace subdfit::fit
