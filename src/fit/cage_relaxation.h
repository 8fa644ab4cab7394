#pragma once
// Keeps a cage clean while the images move it. The images constrain a control vertex along the
// limit surface's normal; along the surface they barely see it, so noise there (a noised start,
// SGE's own noise) stays or grows while the surface improves. Each step, every vertex slides a
// fraction of the way *within its tangent plane* towards where it sat among its neighbours in
// the start cage, low-passed (restOffsets below): the cage relaxes in its own sense, keeping
// its layout but not its noise, without changing the shape the images fitted. Creases are
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
    std::vector<int> modes;                   // per vertex
    std::vector<int> offsets, neighbors;      // CSR: the vertices each one averages
    std::vector<int> cornerOffsets, corners;  // CSR of (previous, next) pairs: the face corners at a vertex
};
RelaxationTopology relaxationTopology(const mesh::PolygonMesh& cage);

// Where each vertex sits relative to the centroid of the vertices it averages, low-passed by
// `passes` rounds of averaging with those neighbours. A cage's own layout (denser rings near a
// feature, a crease chain's spacing) varies smoothly from vertex to vertex and survives the
// low pass; noise (a noised start, SGE's random walk) does not. Relaxing towards centroid + this
// keeps the first and removes the second; towards the bare centroid would even out the layout.
std::vector<glm::vec3> restOffsets(const mesh::PolygonMesh& cage, const RelaxationTopology& topology, int passes);

class CageRelaxation {
public:
    // Relaxes towards centroid + restOffsets(cage, ..., restPasses) (< 0: the bare centroid).
    explicit CageRelaxation(const mesh::PolygonMesh& cage, int restPasses = kRestPasses);

    // Three rounds of averaging: on noised creased cages the bare centroid leaves the vertex
    // error equal or worse where this lowers it (subdfit-bench recovery, docs/measurements.md).
    static constexpr int kRestPasses = 3;

    // θ += rate · (tangential move towards the neighbours' centroid), every vertex at once.
    void apply(gl::ProgramCache& programs, gl::Buffer& theta, float rate);
    // gradient −= (1 − keep) · (its tangential part at θ), in place.
    void projectGradient(gl::ProgramCache& programs, const gl::Buffer& theta, gl::Buffer& gradient, float keep);
    // Binds what glsl/tangent_frame.glsl reads (modes, neighbours, face corners), for a pass of
    // another's that projects too (optim::updateVertices).
    void bindTangentFrame() const;

private:
    void dispatchOverVertices();  // binds the topology, one thread per vertex

    int vertexCount_;
    gl::Buffer modes_, offsets_, neighbors_, cornerOffsets_, corners_, rest_, scratch_;
};

}  // namespace subdfit::fit
