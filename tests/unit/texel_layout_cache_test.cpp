// buildTexelLayout keeps the layouts of the last few cages: a cage laid out again gets the same
// layout, and one of the same topology with other positions gets its own (tile borders are
// welded where their limit points meet, so positions are part of what a layout depends on).
#include <gtest/gtest.h>

#include <utility>

#include "mesh/procedural.h"
#include "surface/texel_layout.h"

namespace subdfit::test {
namespace {

void expectSameLayout(const surface::TexelLayout& a, const surface::TexelLayout& b) {
    EXPECT_EQ(a.resolution, b.resolution);
    EXPECT_EQ(a.nodeCount, b.nodeCount);
    EXPECT_EQ(a.faceNodes, b.faceNodes);
    EXPECT_EQ(a.halo, b.halo);
}

TEST(TexelLayoutCache, ACageLaidOutAgainGetsTheSameLayout) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    const surface::TexelLayout first = surface::buildTexelLayout(cage, 4);
    const mesh::PolygonMesh copy = cage;
    expectSameLayout(surface::buildTexelLayout(copy, 4), first);
    EXPECT_EQ(surface::buildTexelLayout(cage, 2).resolution, 2);  // another resolution is another layout
}

TEST(TexelLayoutCache, OtherPositionsOnTheSameTopologyGetTheirOwnLayout) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    const surface::TexelLayout spread = surface::buildTexelLayout(cage, 3);
    mesh::PolygonMesh collapsed = cage;  // every limit point in one place: every border node welds into one
    for (auto& p : collapsed.positions) p = glm::vec3(0.25f);
    const surface::TexelLayout pinched = surface::buildTexelLayout(collapsed, 3);
    EXPECT_LT(pinched.nodeCount, spread.nodeCount);
    expectSameLayout(surface::buildTexelLayout(cage, 3), spread);
}

// Welding tolerates rounding relative to the shape's size, not to its coordinates: a cage far from
// the origin (where every border node once welded into one), or a tiny one, is laid out alike.
TEST(TexelLayoutCache, ALayoutDependsOnTheShapeNotOnWhereItStands) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    const surface::TexelLayout home = surface::buildTexelLayout(cage, 4);
    for (const auto& [scale, offset] :
         {std::pair{1.0f, glm::vec3(1e5f, -3e4f, 2e5f)}, std::pair{1e-4f, glm::vec3(0.3f)}}) {
        mesh::PolygonMesh moved = cage;
        for (auto& p : moved.positions) p = p * scale + offset;
        expectSameLayout(surface::buildTexelLayout(moved, 4), home);
    }
}

}  // namespace
}  // namespace subdfit::test
