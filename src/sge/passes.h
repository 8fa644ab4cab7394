#pragma once
// G, the estimator of stochastic gradient estimation: per pixel, the loss difference of the
// ± renders goes to the parameters that produced the pixel (gradient.comp, scatter_sums.comp, scatter_vertices.comp).
// P and the updates that use G's sums live in optim/; the rasterisation R in render/.
#include <cstdint>
#include <vector>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/texture.h"
#include "render/render_target.h"
#include "optim/parameter_group.h"

namespace subdfit::maps {
class MapParameters;
}

namespace subdfit::sge {

// Which base vertices reach which ptex face (CSR, each face's sorted), and G's Δ sums: one per
// ptex face, then one per pair of ptex faces that share a base vertex (the pixels that one render
// gave to each of them, whose Δ goes to the union of their vertices).
struct FaceVertexTable {
    FaceVertexTable(const std::vector<int>& faceOffsets, const std::vector<int>& faceVertices, int vertexCount);
    gl::Buffer faceOffsets, faceVertices;  // ptex face -> its base vertices
    gl::Buffer pairFaces;                  // pair k's faces (a, b), a < b (sge/face_pairs.h); its sum is faceCount + k
    gl::Buffer pairRegions, pairSlots;     // the pairs hashed by b in runs of slots per face a
    // How the passes read them: G the hashed pairs, the hand-off the rest.
    gl::BufferTexture faceOffsetsView, faceVerticesView, pairFacesView, pairRegionsView, pairSlotsView;
    gl::Buffer faceDelta;    // one fixed-point sum (two uints) per ptex face, then per pair
    gl::Buffer vertexDelta;  // one fixed-point sum per base vertex: the sums that include it
    int faceCount, pairCount, vertexCount;
};

struct GradientInputs {
    const render::RenderTarget* plus;  // laid out with the face ids in alpha
    const render::RenderTarget* minus;
    const gl::Texture* targets;  // the target colours, a layer per view
    int targetLayer;
    std::uint32_t counter, seed;
    float lossScale;                      // weight of each pixel's loss in the reported mean
    bool measureLoss;                     // also accumulate the loss (costs a target fetch on background pixels)
    maps::MapParameters* maps = nullptr;  // the texel groups' lattices, when the scene has them
    bool fullImage = false;               // plain SPSA (every pixel to every vertex): benchmarks only
};

// G for the perturbed `group`: accumulates Δ_p / (2 s_i ε) into group.gradientSum (vertices:
// through faces.faceDelta; a texel group: into the nodes under each pixel) and the mean loss into the 256 slots of `loss`.
void accumulateGradient(gl::ProgramCache& programs, optim::ParameterGroup& group, const FaceVertexTable& faces,
                        const GradientInputs& inputs, const gl::Buffer& loss);

// G, second half of a vertex turn: hands the per-face and per-pair sums to their vertices, then
// to the vertices' parameters (signs of `counter`), and clears them. Once per perturbation
// sample, after all its views.
void scatterFaceDeltas(gl::ProgramCache& programs, optim::ParameterGroup& group, FaceVertexTable& faces,
                       std::uint32_t counter, std::uint32_t seed, bool fullImage = false);

}  // namespace subdfit::sge
