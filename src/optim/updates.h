#pragma once
// The passes that change a parameter group, each a thin wrapper over its shader in glsl/: P
// (perturb.comp), the resolve of G's fixed-point sums (resolve_gradient.comp), the Laplacian
// preconditioner (precondition.comp) and Adam (adam.comp, shared_moment.comp); and, for a small
// cage, all of the update in one (vertex_update.comp). G itself, which reads renders, is the
// estimator's (sge/).
#include <cstdint>
#include <functional>
#include <utility>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/texture.h"
#include "optim/parameter_group.h"

namespace subdfit::optim {

// P: θ± = θ ± s⊙ε with s drawn from (parameter, counter, seed).
void perturb(gl::ProgramCache& programs, ParameterGroup& group, std::uint32_t counter, std::uint32_t seed);

// group.gradient = the fixed-point sums of G as floats (the sums are left as they are).
void resolveGradient(gl::ProgramCache& programs, ParameterGroup& group);

// The group's parameter graph (CSR); each node holds group.count() / vertexCount floats.
struct Adjacency {
    Adjacency(gl::Buffer offsets_, gl::Buffer indices_, int vertexCount_)
        : offsets(std::move(offsets_)),
          indices(std::move(indices_)),
          offsetsView(offsets, GL_R32I),
          indicesView(indices, GL_R32I),
          vertexCount(vertexCount_) {}
    gl::Buffer offsets, indices;
    gl::BufferTexture offsetsView, indicesView;  // as the preconditioner reads them
    int vertexCount;                             // graph nodes
};

// g̃ = (I + λL)⁻¹ g by `iterations` Jacobi sweeps into group.gradientSmooth (a plain copy when
// iterations == 0 or λ == 0): a small group's in one dispatch, a larger one's a dispatch per
// sweep. `scratch` must be the size of the gradient.
void precondition(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency, float lambda,
                  int iterations, gl::Buffer& scratch);

// Where a vertex gradient keeps only part of its component along the surface (g −= (1 − keep) P g,
// glsl/tangent_frame.glsl): `bind` binds the cage's topology, as fit::CageRelaxation holds it.
struct TangentialProjection {
    std::function<void()> bind;
    float keep;
};

// Whether a group of vertex positions is small enough for updateVertices' one work group.
bool updatesInOneGroup(const ParameterGroup& group);

// A small vertex group's whole update in one dispatch (glsl/vertex_update.comp): G's sums
// resolved and cleared, preconditioned as precondition() does, projected where `projection` is
// given, and Adam's step at `learningRate`, with the results of the passes apart.
void updateVertices(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency, float lambda,
                    int iterations, const TangentialProjection* projection, float learningRate);

// Adam on θ from `gradient` (group.gradient, or group.gradientSmooth after preconditioning),
// with step size `learningRate` (the group's, annealed by the caller). The raw gradient is left
// as it is: the next resolveGradient overwrites all of it.
void adamStep(gl::ProgramCache& programs, ParameterGroup& group, const gl::Buffer& gradient, float learningRate);

}  // namespace subdfit::optim
