#pragma once
// The compute passes of one SGE step, each a thin wrapper over its shader in glsl/:
// P (perturb.comp), G (gradient.comp), the Laplacian preconditioner (precondition.comp) and
// Adam (adam.comp). The rasterisation R between P and G lives in render/.
#include <cstdint>
#include <vector>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "render/render_target.h"
#include "sge/parameter_group.h"

namespace subdfit::maps {
class MapParameters;
}

namespace subdfit::sge {

// P: θ± = θ ± s⊙ε with s drawn from (parameter, counter, seed).
void perturb(gl::ProgramCache& programs, ParameterGroup& group, std::uint32_t counter, std::uint32_t seed);

// Which base vertices reach which ptex face, both ways (CSR), plus the per-face Δ sums of G.
struct FaceVertexTable {
    FaceVertexTable(const std::vector<int>& faceOffsets, const std::vector<int>& faceVertices, int vertexCount);
    gl::Buffer offsets, indices;              // ptex face -> base vertices
    gl::Buffer vertexOffsets, vertexFaces;    // base vertex -> ptex faces
    gl::Buffer faceDelta;                     // one fixed-point sum (two uints) per ptex face
    int vertexCount;
};

struct GradientInputs {
    const render::RenderTarget* plus;
    const render::RenderTarget* minus;
    GLuint targetArray;  // GL_TEXTURE_2D_ARRAY of target colours
    int targetLayer;
    std::uint32_t counter, seed;
    float lossScale;     // weight of each pixel's loss in the reported mean
    bool measureLoss;    // also accumulate the loss (costs a target fetch on background pixels)
    maps::MapParameters* maps = nullptr;  // texel groups to credit too, when the scene has them
    bool fullImage = false;  // plain SPSA (every pixel to every vertex): benchmarks only
};

// G: accumulates Δ_p / (2 s_i ε) into group.gradientSum (directly where the ± faces differ, via
// faces.faceDelta where they agree) and the mean loss into the 256 slots of `loss`.
void accumulateGradient(gl::ProgramCache& programs, ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& inputs, const gl::Buffer& loss);

// G, second half: hands the per-face sums to the vertices' parameters (signs of `counter`)
// and clears them. Once per perturbation sample, after all its views.
void scatterFaceDeltas(gl::ProgramCache& programs, ParameterGroup& group, FaceVertexTable& faces,
                       std::uint32_t counter, std::uint32_t seed, bool fullImage = false);

// group.gradient = the fixed-point sums of G as floats (the sums are left as they are).
void resolveGradient(gl::ProgramCache& programs, ParameterGroup& group);

// g̃ = (I + λL)⁻¹ g by `iterations` Jacobi sweeps into group.gradientSmooth (a plain copy when
// iterations == 0 or λ == 0). `scratch` must be the size of the gradient.
// The group's parameter graph (CSR); each node holds group.count() / vertexCount floats.
struct Adjacency {
    gl::Buffer offsets, indices;
    int vertexCount;  // graph nodes
};
void precondition(gl::ProgramCache& programs, ParameterGroup& group, const Adjacency& adjacency,
                  float lambda, int iterations, gl::Buffer& scratch);

// Adam on θ from `gradient` (group.gradient, or group.gradientSmooth after preconditioning);
// then clears the raw gradient for the next step.
void adamStep(gl::ProgramCache& programs, ParameterGroup& group, const gl::Buffer& gradient);

}  // namespace subdfit::sge
