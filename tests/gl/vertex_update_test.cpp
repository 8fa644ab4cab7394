// A small cage's vertex update in one dispatch (optim::updateVertices, glsl/vertex_update.comp)
// against the passes it stands for, run apart: resolve, precondition, the tangential projection,
// the shared moment and Adam, the sums cleared. Same sums in, the same θ and moments out, step
// after step, on a closed cage and on one with a boundary (crease and fixed vertices).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "fit/cage_relaxation.h"
#include "gl_test_context.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/procedural.h"
#include "optim/updates.h"

namespace subdfit::test {
namespace {

std::vector<float> flatten(const std::vector<glm::vec3>& points) {
    std::vector<float> values;
    for (const auto& p : points) values.insert(values.end(), {p.x, p.y, p.z});
    return values;
}

// G's fixed-point sums (glsl/fixed_point.glsl: low word, then high) of `values`.
std::vector<std::uint32_t> fixedSums(const std::vector<float>& values) {
    std::vector<std::uint32_t> sums;
    for (float x : values) {
        const double whole = std::floor(double(x));
        sums.push_back(std::uint32_t((double(x) - whole) * 4294967296.0));
        sums.push_back(std::uint32_t(std::int32_t(whole)));
    }
    return sums;
}

float largestDifference(const std::vector<float>& a, const std::vector<float>& b) {
    float worst = 0.0f;
    for (size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
    return worst;
}

struct Case {
    optim::GroupSettings settings;
    float keep;  // 1: no projection
};

void expectOneDispatchAsThePasses(const mesh::PolygonMesh& cage, const Case& c) {
    const auto graph = mesh::vertexAdjacency(cage);
    const optim::Adjacency adjacency{gl::Buffer::fromVector(graph.offsets), gl::Buffer::fromVector(graph.neighbors),
                                     cage.vertexCount()};
    fit::CageRelaxation relaxation(cage);
    const auto start = flatten(cage.positions);
    optim::ParameterGroup fused(optim::GroupKind::Vertices, "vertices", start, c.settings);
    optim::ParameterGroup apart(optim::GroupKind::Vertices, "vertices", start, c.settings);
    ASSERT_TRUE(optim::updatesInOneGroup(fused));
    gl::Buffer scratch(apart.gradient.bytes());
    const optim::TangentialProjection projection{[&] { relaxation.bindTangentFrame(); }, c.keep};
    constexpr float kLambda = 4.0f, kRate = 0.01f;
    constexpr int kSweeps = 8;

    std::mt19937 random(11);
    std::normal_distribution<float> noise(0.0f, 3.0f);
    for (int step = 0; step < 4; ++step) {
        std::vector<float> g(start.size());
        for (float& x : g) x = noise(random);
        const auto sums = fixedSums(g);
        for (auto* group : {&fused, &apart})
            group->gradientSum.upload(sums.data(), GLsizeiptr(sums.size() * sizeof(std::uint32_t)));

        optim::updateVertices(programs(), fused, adjacency, kLambda, kSweeps, c.keep < 1.0f ? &projection : nullptr,
                              kRate);
        optim::resolveGradient(programs(), apart);
        optim::precondition(programs(), apart, adjacency, kLambda, kSweeps, scratch);
        if (c.keep < 1.0f) relaxation.projectGradient(programs(), apart.theta, apart.gradientSmooth, c.keep);
        optim::adamStep(programs(), apart, apart.gradientSmooth, kRate);
        apart.gradientSum.clearToZero();

        const auto moved = apart.read();
        const float largestMove = largestDifference(moved, start);
        ASSERT_GT(largestMove, 0.0f);
        EXPECT_LE(largestDifference(fused.read(), moved), 1e-4f * largestMove) << "step " << step;
        EXPECT_LE(largestDifference(fused.gradient.read<float>(), apart.gradient.read<float>()), 1e-6f);
        EXPECT_LE(largestDifference(fused.gradientSmooth.read<float>(), apart.gradientSmooth.read<float>()), 1e-5f);
        EXPECT_LE(largestDifference(fused.moment1.read<float>(), apart.moment1.read<float>()), 1e-5f);
        EXPECT_LE(largestDifference(fused.moment2.read<float>(), apart.moment2.read<float>()), 1e-4f);
        EXPECT_NEAR(fused.groupMoment2.read<float>().at(0), apart.groupMoment2.read<float>().at(0),
                    1e-5f * apart.groupMoment2.read<float>().at(0));
        const auto left = fused.gradientSum.read<std::uint32_t>();
        EXPECT_TRUE(std::all_of(left.begin(), left.end(), [](std::uint32_t x) { return x == 0u; }))
            << "the sums are cleared for the next step";
        EXPECT_EQ(fused.adamSteps, apart.adamSteps);
    }
}

const Case kSharedMomentProjected{{.sharedMoment = true}, 0.2f};
const Case kOwnMomentsGated{{.sharedMoment = false, .noiseGate = 1.0f}, 1.0f};

TEST(VertexUpdate, OneDispatchOnAClosedCageMovesItAsThePassesApart) {
    expectOneDispatchAsThePasses(mesh::makeQuadSphere(6), kSharedMomentProjected);
    expectOneDispatchAsThePasses(mesh::makeQuadSphere(6), kOwnMomentsGated);
}

TEST(VertexUpdate, OneDispatchOnACageWithABoundaryMovesItAsThePassesApart) {
    expectOneDispatchAsThePasses(mesh::makeQuadGrid(9), kSharedMomentProjected);
}

TEST(VertexUpdate, ALargeCageIsLeftToThePassesApart) {
    const auto cage = mesh::makeQuadSphere(20);  // 2 402 vertices: past one work group's floats
    const optim::ParameterGroup group(optim::GroupKind::Vertices, "vertices", flatten(cage.positions), {});
    EXPECT_FALSE(optim::updatesInOneGroup(group));
}

}  // namespace
}  // namespace subdfit::test
