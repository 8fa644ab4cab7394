#pragma once
// The compute passes of one SGE step, each a thin wrapper over its shader in glsl/:
// P (perturb.comp), G (gradient.comp), the Laplacian preconditioner (precondition.comp) and
// Adam (adam.comp). The rasterisation R between P and G lives in render/.
#include <cstdint>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "render/render_target.h"
#include "sge/parameter_group.h"

namespace subdfit::sge {

// P: θ± = θ ± s⊙ε with s drawn from (parameter, counter, seed).
void perturb(gl::ProgramCache& programs, ParameterGroup& group, std::uint32_t counter, std::uint32_t seed);

// Per-pixel face -> contributing parameter table, CSR over base vertices.
struct FaceVertexTable {
    gl::Buffer offsets, indices;
};

struct GradientInputs {
    const render::RenderTarget* plus;
    const render::RenderTarget* minus;
    GLuint targetArray;  // GL_TEXTURE_2D_ARRAY of target colours
    int targetLayer;
    std::uint32_t counter, seed;
    float lossScale;     // weight of each pixel's loss in the reported mean
};

// G: accumulates Δ_p / (2 s_i ε) into group.gradient and the mean loss into `loss` [0].
void accumulateGradient(gl::ProgramCache& programs, ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& inputs, const gl::Buffer& loss);

// g̃ = (I + λL)⁻¹ g by `iterations` Jacobi sweeps into group.gradientSmooth (a plain copy when
// iterations == 0 or λ == 0). `scratch` must be the size of the gradient.
struct Adjacency {
    gl::Buffer offsets, indices;
    int vertexCount;
};
void precondition(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency,
                  float lambda, int iterations, gl::Buffer& scratch);

// Adam on θ from group.gradientSmooth; then clears the raw gradient for the next step.
void adamStep(gl::ProgramCache& programs, ParameterGroup& group);

}  // namespace subdfit::sge
