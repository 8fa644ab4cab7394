// One Catmull-Clark step keeps the limit surface; the relief reference built on it is watertight.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/mesh_loader.h"
#include "subdiv/limit_evaluator.h"
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

// Each child face's corners name where it lies on the cage's ptex faces: the refined cage's
// limit surface at a child's (a, b) is the cage's at the bilinear blend of those corners. The
// refined cage is evaluated one isolation level shallower, so that both use the same patches
// (semi-sharp creases included).
class RefinedPtex : public ::testing::TestWithParam<const char*> {};

TEST_P(RefinedPtex, ChildFacesMapOntoThePtexFacesExactly) {
    const auto cage = mesh::loadMesh(test::assetPath(GetParam()));
    const auto refined = subdiv::refinedOnceWithPtex(cage);
    ASSERT_EQ(refined.ptexFace.size(), size_t(refined.mesh.faceCount()));
    const subdiv::LimitEvaluator ours(cage, {.isolationLevel = 3}), theirs(refined.mesh, {.isolationLevel = 2});
    float size = 0.0f;
    for (const auto& p : cage.positions) size = std::max(size, glm::length(p));
    int compared = 0;
    for (int f = 0; f < refined.mesh.faceCount(); ++f)
        for (const glm::vec2 ab :
             {glm::vec2(0.5f), glm::vec2(0.1f, 0.8f), glm::vec2(0.9f, 0.3f), glm::vec2(1.0f, 0.0f)}) {
            const glm::vec2* c = &refined.cornerUv[4 * size_t(f)];
            const glm::vec2 uv = glm::mix(glm::mix(c[0], c[1], ab.x), glm::mix(c[3], c[2], ab.x), ab.y);
            const int ptex = refined.ptexFace[size_t(f)];
            ASSERT_EQ(theirs.hasSurface(f, ab.x, ab.y), ours.hasSurface(ptex, uv.x, uv.y)) << "face " << f;
            if (!theirs.hasSurface(f, ab.x, ab.y)) continue;
            const auto a = theirs.evaluate(f, ab.x, ab.y, refined.mesh.positions);
            const auto b = ours.evaluate(ptex, uv.x, uv.y, cage.positions);
            ASSERT_LT(glm::length(a.position - b.position), 1e-5f * size)
                << "face " << f << " at " << ab.x << ", " << ab.y;
            ++compared;
        }
    EXPECT_GT(compared, refined.mesh.faceCount());
}

std::string shapeName(const ::testing::TestParamInfo<const char*>& info) {
    std::string name = info.param;
    name = name.substr(name.find('/') + 1);
    return name.substr(0, name.find('.'));
}

INSTANTIATE_TEST_SUITE_P(Shapes, RefinedOnce,
                         ::testing::Values("spot/spot_control_mesh.obj", "osd-shapes/catmark_inf_crease0.obj",
                                           "osd-shapes/catmark_hole_test1.obj"),
                         shapeName);
INSTANTIATE_TEST_SUITE_P(Shapes, RefinedPtex,
                         ::testing::Values("spot/spot_control_mesh.obj", "osd-shapes/catmark_inf_crease0.obj",
                                           "osd-shapes/catmark_hole_test1.obj", "osd-shapes/catmark_smoothtris0.obj",
                                           "osd-shapes/catmark_edgecorner.obj",
                                           "osd-shapes/catmark_pyramid_creases2.obj"),
                         shapeName);

// Spot has triangles and pentagons beside its quads; tessellated as they are, their per-corner
// tiles meet a quad's edge at twice its samples (T-junctions, 3 888 open edges at 24 segments).
TEST(ReliefSurface, IsDenseAndWatertight) {
    const auto relief = surface::reliefSurface(mesh::loadMesh(test::assetPath("spot/spot_control_mesh.obj")));
    EXPECT_GT(relief.faceCount(), 200000);
    EXPECT_EQ(openEdges(relief), 0);
}

// Relief in patches: about `coverage` of the surface moves (and a fade around the patches), the
// rest stays the smooth base.
TEST(ReliefSurface, CoversTheShareOfTheSurfaceAsked) {
    const auto cage = mesh::loadMesh(test::assetPath("spot/spot_control_mesh.obj"));
    const auto base = surface::reliefSurface(cage, {.segments = 8, .amplitude = 0.0f});
    for (const float coverage : {0.0f, 0.35f, 1.0f}) {
        const auto relief = surface::reliefSurface(cage, {.segments = 8, .coverage = coverage});
        ASSERT_EQ(relief.positions.size(), base.positions.size());
        size_t moved = 0;
        for (size_t v = 0; v < base.positions.size(); ++v)
            moved += glm::distance(relief.positions[v], base.positions[v]) > 1e-6f;
        const double share = double(moved) / double(base.positions.size());
        EXPECT_GE(share, coverage - 0.02) << "coverage " << coverage;
        EXPECT_LE(share, coverage > 0.0f ? coverage + 0.1 : 0.0) << "coverage " << coverage;
    }
}

}  // namespace
}  // namespace subdfit
