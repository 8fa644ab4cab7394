// The tessellation the patch renderer evaluates and draws: every patch a grid of L = T / 2^depth
// segments a side, and no crack where patches of different depths meet inside a ptex face.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <tuple>

#include "mesh/obj_reader.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"
#include "render/patch_tessellation.h"
#include "render/patch_renderer.h"
#include "test_paths.h"

namespace subdfit::render {
namespace {

struct Cage {
    const char* name;
    mesh::PolygonMesh mesh;
};

std::vector<Cage> cages() {
    return {{"pyramid (n-gons, creases)", mesh::readObj(test::assetPath("osd-shapes/catmark_pyramid_creases2.obj"))},
            {"spot (extraordinary vertices)", mesh::readObj(test::assetPath("spot/spot_control_mesh.obj"))},
            {"triangles", mesh::triangulated(mesh::makeQuadSphere(3))}};
}

// Where a vertex lies on its ptex face, exactly: in units of 1 / (T · 2^depth) of the face.
using PtexPoint = std::tuple<int, long, long>;

PtexPoint ptexPoint(const subdiv::PatchSet& patches, glm::ivec2 sample, int tessLevel) {
    const auto param = patches.patchParam(sample.x);
    const int level = sample.y >> 16, i = sample.y & 0xff, j = (sample.y >> 8) & 0xff;
    // The patch spans [u0, u0 + 1/2^d) of the face (a non-quad's face split counts in d); its
    // vertex i of L sits at u0 + i / (L · 2^d).
    const int depth = param.GetDepth() - (param.NonQuadRoot() ? 1 : 0);
    const long unit = long(tessLevel) << 12;  // finer than any patch's segment
    const long scale = unit >> depth;
    return {param.GetFaceId(), long(param.GetU()) * scale + i * scale / level, long(param.GetV()) * scale + j * scale / level};
}

TEST(PatchTessellation, EveryPatchIsAGridOfItsDepthsSegments) {
    for (const auto& cage : cages()) {
        const auto patches = subdiv::buildPatchSet(cage.mesh);
        const int tess = crackFreeTessLevel(4, patches.maxPatchDepth);
        const PatchTessellation t = tessellatePatches(patches, tess);
        std::map<int, int> verticesOf;
        for (const auto& s : t.samples) ++verticesOf[s.x];
        ASSERT_EQ(int(verticesOf.size()), patches.patchCount()) << cage.name;
        size_t quads = 0;
        for (const auto& [patch, count] : verticesOf) {
            const int level = std::max(1, tess >> patches.patchParam(patch).GetDepth());
            EXPECT_EQ(count, (level + 1) * (level + 1)) << cage.name << ", patch " << patch;
            quads += size_t(level * level);
        }
        EXPECT_EQ(t.quads.size(), 4 * quads) << cage.name;
        for (std::uint32_t v : t.quads) ASSERT_LT(v, t.samples.size()) << cage.name;
        // The runs cover every vertex once, each of one patch kind.
        int next = 0;
        for (const auto& run : t.runs) {
            EXPECT_EQ(run.first, next) << cage.name;
            for (int k = run.first; k < run.first + run.count; ++k)
                EXPECT_EQ(patches.patchInfo[t.samples[k].x].y == subdiv::kGregoryBasisPatch, run.gregory) << cage.name;
            next = run.first + run.count;
        }
        EXPECT_EQ(next, int(t.samples.size())) << cage.name;
    }
}

// Where patches meet inside a ptex face, each has a vertex wherever the other has one on their
// common edge (the crack-free levels): with fewer segments on one side, the other side's extra
// vertices would be T-junctions, pinholes at the seam.
TEST(PatchTessellation, PatchesMeetVertexForVertexInsideAFace) {
    for (const auto& cage : cages()) {
        const auto patches = subdiv::buildPatchSet(cage.mesh);
        const int tess = crackFreeTessLevel(4, patches.maxPatchDepth);
        ASSERT_GE(patches.maxPatchDepth, 2) << cage.name;  // patches of several depths meet
        const PatchTessellation t = tessellatePatches(patches, tess);
        // Each patch's square on its face, and its vertices there.
        struct Square {
            long u0, v0, span;
        };
        std::map<int, std::vector<int>> patchesOfFace;
        std::map<int, Square> squares;
        std::set<std::pair<int, PtexPoint>> vertices;
        for (const auto& s : t.samples) {
            const PtexPoint at = ptexPoint(patches, s, tess);
            vertices.insert({s.x, at});
            if (squares.count(s.x)) continue;
            const PtexPoint corner = ptexPoint(patches, {s.x, (s.y >> 16) << 16}, tess);
            const PtexPoint far = ptexPoint(patches, {s.x, (s.y >> 16) << 16 | (s.y >> 16) | (s.y >> 16) << 8}, tess);
            squares[s.x] = {std::get<1>(corner), std::get<2>(corner), std::get<1>(far) - std::get<1>(corner)};
            patchesOfFace[std::get<0>(corner)].push_back(s.x);
        }
        const long faceSpan = long(tess) << 12;
        int checked = 0;
        for (const auto& [patch, at] : vertices) {
            const auto [face, u, v] = at;
            if (u <= 0 || v <= 0 || u >= faceSpan || v >= faceSpan) continue;  // on the face's own edge
            for (int other : patchesOfFace[face]) {
                const Square& q = squares[other];
                const bool inside = u >= q.u0 && u <= q.u0 + q.span && v >= q.v0 && v <= q.v0 + q.span;
                const bool onBorder = u == q.u0 || u == q.u0 + q.span || v == q.v0 || v == q.v0 + q.span;
                if (other == patch || !inside || !onBorder) continue;
                ++checked;
                EXPECT_TRUE(vertices.count({other, at})) << cage.name << ": patch " << patch << "'s vertex at (" << u << ", " << v
                                                         << ") of face " << face << " is no vertex of patch " << other;
            }
        }
        EXPECT_GT(checked, 100) << cage.name;
    }
}

}  // namespace
}  // namespace subdfit::render
