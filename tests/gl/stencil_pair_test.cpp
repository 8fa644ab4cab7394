// A step evaluates θ+ and θ− in one dispatch: each set must come out exactly as it does alone.
#include <gtest/gtest.h>

#include <vector>

#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "render/stencil_evaluator.h"
#include "subdiv/patch_set.h"

namespace subdfit::render {
namespace {

std::vector<float> shifted(const mesh::PolygonMesh& mesh, float by) {
    std::vector<float> flat;
    for (const auto& p : mesh.positions) flat.insert(flat.end(), {p.x + by, p.y - by, p.z});
    return flat;
}

TEST(StencilPair, EachSetMatchesItsOwnEvaluationBitForBit) {
    const auto cage = mesh::makeQuadSphere(3);
    const auto patches = subdiv::buildPatchSet(cage);
    const StencilEvaluator stencils(patches);
    const auto plus = gl::Buffer::fromVector(shifted(cage, 0.01f));
    const auto minus = gl::Buffer::fromVector(shifted(cage, -0.01f));
    const auto alonePlus = stencils.makePointBuffer(), aloneMinus = stencils.makePointBuffer();
    const auto pairPlus = stencils.makePointBuffer(), pairMinus = stencils.makePointBuffer();
    stencils.evaluate(test::programs(), plus, alonePlus);
    stencils.evaluate(test::programs(), minus, aloneMinus);
    stencils.evaluate(test::programs(), plus, pairPlus, minus, pairMinus);

    const auto expectedPlus = alonePlus.read<float>(), expectedMinus = aloneMinus.read<float>();
    ASSERT_EQ(expectedPlus.size(), size_t(3 * stencils.pointCount()));
    EXPECT_NE(expectedPlus, expectedMinus);  // the sets differ, so a swap or a copy would show
    EXPECT_EQ(pairPlus.read<float>(), expectedPlus);
    EXPECT_EQ(pairMinus.read<float>(), expectedMinus);
    test::expectNoGlError();
}

}  // namespace
}  // namespace subdfit::render
