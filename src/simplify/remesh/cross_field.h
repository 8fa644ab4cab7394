#pragma once
// The two fields of a field-aligned quad remesher (Jakob et al. 2015), on the samples of a
// surface hierarchy:
//   orientation  a unit tangent q per sample, meaning the four directions ±q, ±(n × q): the way
//                the quads' edges run. Smoothed so that neighbours' closest pair of directions
//                agree (4-RoSy: a quad's edges are the same after a quarter turn).
//   position     a point o per sample in its tangent plane, meaning the lattice
//                o + s·(i·q + j·(n × q)): where the quads' corners sit, s apart. Smoothed so that
//                neighbours' lattices share their nearest points, then moved to the lattice point
//                nearest the sample.
// Both are smoothed coarse to fine by Gauss-Seidel sweeps; everything is deterministic.
#include <glm/vec3.hpp>
#include <vector>

#include "simplify/remesh/surface_graph.h"

namespace subdfit::simplify::remesh {

// Gauss-Seidel sweeps per level: many where a level is small (cheap, and where the field finds
// its shape), few on the large fine levels, which only settle what the coarser ones carried down.
struct FieldSweeps {
    int orientation = 24, position = 24;        // on levels of up to `smallLevel` samples
    int fineOrientation = 4, finePosition = 6;  // on larger ones
    int smallLevel = 4096;
};

// One q per sample of levels[0].
std::vector<glm::vec3> orientationField(const std::vector<GraphLevel>& levels, const FieldSweeps& sweeps = {});

// One o per sample of levels[0], the lattice spaced by each sample's scale (two samples compare
// their lattices at their mean scale); `orientation` from orientationField (it is carried to the
// coarser levels by averaging).
std::vector<glm::vec3> positionField(const std::vector<GraphLevel>& levels, const std::vector<glm::vec3>& orientation,
                                     const FieldSweeps& sweeps = {});

// The pair of the four directions of (q0, n0) and of (q1, n1) closest to parallel, the second
// signed to agree with the first.
std::pair<glm::vec3, glm::vec3> closestDirections(const glm::vec3& q0, const glm::vec3& n0, const glm::vec3& q1,
                                                  const glm::vec3& n1);

// The integer lattice step (i, j) from sample a's lattice point to sample b's, in a's frame.
struct LatticeStep {
    int i = 0, j = 0;
};
LatticeStep latticeStep(const glm::vec3& oa, const glm::vec3& qa, const glm::vec3& na, const glm::vec3& ob,
                        float scale);

}  // namespace subdfit::simplify::remesh
