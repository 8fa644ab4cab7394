// A step evaluates θ+ and θ− together, their points in one dispatch and their surfaces in one
// dispatch per patch kind: each must come out exactly as it does alone.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "gl_test_context.h"
#include "mesh/procedural.h"
#include "maps/map_parameters.h"
#include "render/patch_renderer.h"
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

// θ+'s and θ−'s surfaces evaluated together, and each alone: the same vertices and triangles, to
// the bit, with heights (as a vertex turn of a scene with displacement draws) and without.
void expectPairMatchesAlone(const PatchMaps* maps, const mesh::PolygonMesh& cage, const PatchRenderer& renderer,
                            const StencilEvaluator& stencils) {
    const auto plus = stencils.makePointBuffer(), minus = stencils.makePointBuffer();
    stencils.evaluate(test::programs(), gl::Buffer::fromVector(shifted(cage, 0.01f)), plus);
    stencils.evaluate(test::programs(), gl::Buffer::fromVector(shifted(cage, -0.01f)), minus);
    const auto alonePlus = renderer.makeSurface(), aloneMinus = renderer.makeSurface();
    const auto pairPlus = renderer.makeSurface(), pairMinus = renderer.makeSurface();
    renderer.evaluate(test::programs(), plus, alonePlus, maps);
    renderer.evaluate(test::programs(), minus, aloneMinus, maps);
    renderer.evaluatePair(test::programs(), plus, pairPlus, minus, pairMinus, maps);

    const auto expectedPlus = alonePlus.vertices.read<float>(), expectedMinus = aloneMinus.vertices.read<float>();
    EXPECT_NE(expectedPlus, expectedMinus);
    EXPECT_EQ(pairPlus.vertices.read<float>(), expectedPlus);
    EXPECT_EQ(pairMinus.vertices.read<float>(), expectedMinus);
    EXPECT_EQ(pairPlus.triangles.read<std::uint32_t>(), alonePlus.triangles.read<std::uint32_t>());
    EXPECT_EQ(pairMinus.triangles.read<std::uint32_t>(), aloneMinus.triangles.read<std::uint32_t>());
    test::expectNoGlError();
}

TEST(SurfacePair, EachSurfaceMatchesItsOwnEvaluationBitForBit) {
    const auto cage = mesh::makeQuadSphere(3);  // valence-3 corners: Gregory patches beside regular ones
    const auto patches = subdiv::buildPatchSet(cage);
    const StencilEvaluator stencils(patches);
    expectPairMatchesAlone(nullptr, cage, PatchRenderer(patches, 4), stencils);

    maps::MapParameters heights(cage, {maps::MapKind::Displacement}, {.resolution = 4});
    std::vector<float> values(size_t(heights.displacement()->count()));
    for (size_t i = 0; i < values.size(); ++i) values[i] = 0.02f * std::sin(0.7f * float(i));
    heights.displacement()->write(values);
    const PatchMaps maps = heights.forRaster(maps::ParameterVersion::Current);
    const PatchRenderer renderer(patches, 4);
    expectPairMatchesAlone(&maps, cage, renderer, stencils);
    // The heights moved the surface: the case above is not the one without them again.
    const auto points = stencils.makePointBuffer();
    stencils.evaluate(test::programs(), gl::Buffer::fromVector(shifted(cage, 0.0f)), points);
    const auto bare = renderer.makeSurface(), displaced = renderer.makeSurface();
    renderer.evaluate(test::programs(), points, bare);
    renderer.evaluate(test::programs(), points, displaced, &maps);
    EXPECT_NE(bare.vertices.read<float>(), displaced.vertices.read<float>());
}

}  // namespace
}  // namespace subdfit::render
