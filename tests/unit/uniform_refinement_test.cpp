// One Catmull-Clark step keeps the limit surface; the relief reference built on it is watertight.
#include <gtest/gtest.h>

#include <map>

#include <glm/geometric.hpp>

#include "mesh/mesh_loader.h"
#include "subdiv/uniform_refinement.h"
#include "surface/relief_surface.h"
#include "surface/tessellation.h"
#include "test_paths.h"

namespace subdfit {
namespace {

double area(const mesh::PolygonMesh& triangles) {
    double sum = 0.0;
    for (size_t t = 0; t + 2 < triangles.faceIndices.size(); t += 3) {
        auto p = [&](size_t k) { return triangles.positions[size_t(triangles.faceIndices[t + k])]; };
        sum += 0.5 * double(glm::length(glm::cross(p(1) - p(0), p(2) - p(0))));
    }
    return sum;
}

// Edges used by one triangle only: cracks, in a surface that should have none.
int openEdges(const mesh::PolygonMesh& triangles) {
    std::map<std::pair<int, int>, int> uses;
    for (size_t t = 0; t + 2 < triangles.faceIndices.size(); t += 3)
        for (size_t k = 0; k < 3; ++k) {
            const int a = triangles.faceIndices[t + k], b = triangles.faceIndices[t + (k + 1) % 3];
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    int open = 0;
    for (const auto& [edge, count] : uses) open += count == 1;
    return open;
}

// (Creases here are infinitely sharp: a semi-sharp one is approximated by the adaptive patches'
// isolation depth, which one step of refinement shifts, so its limit differs by more than the
// refinement.)
class RefinedOnce : public ::testing::TestWithParam<const char*> {};

TEST_P(RefinedOnce, IsAllQuadsWithTheSameLimitSurface) {
    const auto cage = mesh::loadMesh(test::assetPath(GetParam()));
    const auto refined = subdiv::refinedOnce(cage);
    int corners = 0;
    for (int n : cage.faceSizes) corners += n;
    EXPECT_EQ(refined.faceCount(), corners);
    for (int n : refined.faceSizes) ASSERT_EQ(n, 4);
    // A quad's ptex tile at 8 segments holds the points of its four children at 4.
    const double before = area(surface::limitMesh(cage, 8)), after = area(surface::limitMesh(refined, 4));
    EXPECT_NEAR(after, before, 2e-3 * before);
    EXPECT_EQ(refined.tags.creases.empty(), cage.tags.creases.empty());
}

INSTANTIATE_TEST_SUITE_P(Shapes, RefinedOnce,
                         ::testing::Values("spot/spot_control_mesh.obj", "osd-shapes/catmark_inf_crease0.obj",
                                           "osd-shapes/catmark_hole_test1.obj"),
                         [](const auto& info) {
                             std::string name = info.param;
                             name = name.substr(name.find('/') + 1);
                             return name.substr(0, name.find('.'));
                         });

// Spot has triangles and pentagons beside its quads; tessellated as they are, their per-corner
// tiles meet a quad's edge at twice its samples (T-junctions, 3 888 open edges at 24 segments).
TEST(ReliefSurface, IsDenseAndWatertight) {
    const auto relief = surface::reliefSurface(mesh::loadMesh(test::assetPath("spot/spot_control_mesh.obj")));
    EXPECT_GT(relief.faceCount(), 200000);
    EXPECT_EQ(openEdges(relief), 0);
}

}  // namespace
}  // namespace subdfit
