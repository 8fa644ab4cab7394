// The Laplacian preconditioner (glsl/precondition.comp) against the damped Jacobi sweeps done on
// the CPU: a small group's sweeps run in one work group, a large one's a dispatch each, and
// both must give what the formula gives.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "gl_test_context.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/procedural.h"
#include "optim/updates.h"

namespace subdfit::test {
namespace {

// g̃ ← (1 − ω) g̃ + ω (g + λ Σ_neighbours g̃) / (1 + λ|N|), from g̃ = g, `sweeps` times.
std::vector<float> jacobiOnCpu(const mesh::VertexAdjacency& graph, const std::vector<float>& g, int channels,
                               float lambda, int sweeps) {
    const float omega = 2.0f / 3.0f;
    std::vector<float> iterate = g, next(g.size());
    const int nodes = int(graph.offsets.size()) - 1;
    for (int k = 0; k < sweeps; ++k) {
        for (int v = 0; v < nodes; ++v) {
            const int begin = graph.offsets[size_t(v)], end = graph.offsets[size_t(v) + 1];
            const float scale = 1.0f / (1.0f + lambda * float(end - begin));
            for (int c = 0; c < channels; ++c) {
                float neighbourSum = 0.0f;
                for (int n = begin; n < end; ++n)
                    neighbourSum += iterate[size_t(channels * graph.neighbors[size_t(n)] + c)];
                const size_t i = size_t(channels * v + c);
                next[i] = iterate[i] + omega * ((g[i] + lambda * neighbourSum) * scale - iterate[i]);
            }
        }
        iterate.swap(next);
    }
    return iterate;
}

// The GPU's preconditioned gradient of a noisy gradient on `cage`'s vertex graph.
void expectPreconditionedAsOnCpu(const mesh::PolygonMesh& cage, int sweeps) {
    const auto graph = mesh::vertexAdjacency(cage);
    std::mt19937 random(7);
    std::normal_distribution<float> noise;
    std::vector<float> g(size_t(3 * cage.vertexCount()));
    for (float& x : g) x = noise(random);

    optim::ParameterGroup group(optim::GroupKind::Vertices, "vertices", std::vector<float>(g.size()), {});
    group.gradient.upload(g.data(), GLsizeiptr(g.size() * sizeof(float)));
    const optim::Adjacency adjacency{gl::Buffer::fromVector(graph.offsets), gl::Buffer::fromVector(graph.neighbors),
                                     cage.vertexCount()};
    gl::Buffer scratch(group.gradient.bytes());
    constexpr float kLambda = 4.0f;
    optim::precondition(programs(), group, adjacency, kLambda, sweeps, scratch);
    const auto onGpu = group.gradientSmooth.read<float>();
    const auto expected = jacobiOnCpu(graph, g, 3, kLambda, sweeps);

    ASSERT_EQ(onGpu.size(), expected.size());
    double largestError = 0.0, largestValue = 0.0, largestGiven = 0.0;
    for (float x : g) largestGiven = std::max(largestGiven, double(std::abs(x)));
    for (size_t i = 0; i < expected.size(); ++i) {
        ASSERT_TRUE(std::isfinite(onGpu[i])) << "float " << i;
        largestError = std::max(largestError, double(std::abs(onGpu[i] - expected[i])));
        largestValue = std::max(largestValue, double(std::abs(expected[i])));
    }
    EXPECT_LT(largestError, 1e-5 * largestValue) << cage.vertexCount() << " vertices, " << sweeps << " sweeps";
    // The sweeps did smooth: the result is not the gradient it started from.
    EXPECT_LT(largestValue, 0.5 * largestGiven);
}

TEST(Preconditioner, ASmallGroupInOneWorkGroupSweepsAsTheFormula) {
    expectPreconditionedAsOnCpu(mesh::makeQuadSphere(6), 8);   // 218 vertices
    expectPreconditionedAsOnCpu(mesh::makeQuadSphere(6), 13);  // an odd count ends in the other iterate
}

TEST(Preconditioner, ALargeGroupADispatchPerSweepSweepsAsTheFormula) {
    const auto cage = mesh::makeQuadSphere(20);  // 2 402 vertices: 7 206 floats, past one work group's
    ASSERT_GT(3 * cage.vertexCount(), 4096);
    expectPreconditionedAsOnCpu(cage, 8);
    expectPreconditionedAsOnCpu(cage, 13);
}

}  // namespace
}  // namespace subdfit::test
