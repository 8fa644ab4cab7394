// The tessellation the patch renderer evaluates and draws: every patch a grid of L = T / 2^depth
// segments a side, one vertex per point of a ptex face, and no crack where patches of different
// depths meet inside a face.
#include <gtest/gtest.h>

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
    return {param.GetFaceId(), long(param.GetU()) * scale + i * scale / level,
            long(param.GetV()) * scale + j * scale / level};
}

TEST(PatchTessellation, EveryPatchIsAGridOfItsDepthsSegments) {
    for (const auto& cage : cages()) {
        const auto patches = subdiv::buildPatchSet(cage.mesh);
        const int tess = crackFreeTessLevel(4, patches.maxPatchDepth);
        const PatchTessellation t = tessellatePatches(patches, tess);
        // The quads come patch by patch, L × L each, row by row: quad (i, j) of patch p has the
        // corners of its square on the face, whichever patch evaluates them.
        size_t quad = 0;
        for (int p = 0; p < patches.patchCount(); ++p) {
            const int level = std::max(1, tess >> patches.patchParam(p).GetDepth());
            const auto corner = [&](int i, int j) { return ptexPoint(patches, {p, i | j << 8 | level << 16}, tess); };
            for (int j = 0; j < level; ++j)
                for (int i = 0; i < level; ++i, ++quad) {
                    ASSERT_LE(4 * quad + 4, t.quads.size()) << cage.name;
                    const PtexPoint expected[4] = {corner(i, j), corner(i + 1, j), corner(i + 1, j + 1),
                                                   corner(i, j + 1)};
                    for (int k = 0; k < 4; ++k) {
                        const std::uint32_t v = t.quads[4 * quad + size_t(k)];
                        ASSERT_LT(v, t.samples.size()) << cage.name;
                        EXPECT_EQ(ptexPoint(patches, t.samples[v], tess), expected[k]) << cage.name << ", patch " << p;
                    }
                }
        }
        EXPECT_EQ(t.quads.size(), 4 * quad) << cage.name;
        // One vertex per point of a face: patches share the vertices of their common edges.
        std::set<PtexPoint> points;
        for (const auto& s : t.samples) EXPECT_TRUE(points.insert(ptexPoint(patches, s, tess)).second) << cage.name;
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

// Vertices lying inside a quad's edge (not at its ends): T-junctions, pinholes at the seam where
// a patch with fewer segments meets one with more. Returns their count and the edges checked.
std::pair<int, int> tJunctions(const subdiv::PatchSet& patches, const PatchTessellation& t, int tess) {
    std::set<PtexPoint> byRow, byColumn;  // (face, v, u) and (face, u, v)
    for (const auto& s : t.samples) {
        const auto [face, u, v] = ptexPoint(patches, s, tess);
        byRow.insert({face, v, u});
        byColumn.insert({face, u, v});
    }
    const auto strictlyBetween = [](const std::set<PtexPoint>& line, int face, long along, long a, long b) {
        const auto it = line.upper_bound({face, along, std::min(a, b)});
        return it != line.end() && *it < PtexPoint{face, along, std::max(a, b)};
    };
    int found = 0, edges = 0;
    for (size_t q = 0; q < t.quads.size(); q += 4)
        for (size_t k = 0; k < 4; ++k, ++edges) {
            const auto [face, u0, v0] = ptexPoint(patches, t.samples[t.quads[q + k]], tess);
            const auto [face1, u1, v1] = ptexPoint(patches, t.samples[t.quads[q + (k + 1) % 4]], tess);
            found += v0 == v1 ? strictlyBetween(byRow, face, v0, u0, u1) : strictlyBetween(byColumn, face, u0, v0, v1);
        }
    return {found, edges};
}

// Where patches of different depths meet inside a ptex face, each has a vertex wherever the other
// has one on their common edge (the crack-free levels); at half that level they do not.
TEST(PatchTessellation, PatchesMeetVertexForVertexInsideAFace) {
    for (const auto& cage : cages()) {
        const auto patches = subdiv::buildPatchSet(cage.mesh);
        const int tess = crackFreeTessLevel(4, patches.maxPatchDepth);
        ASSERT_GE(patches.maxPatchDepth, 2) << cage.name;  // patches of several depths meet
        const auto [found, edges] = tJunctions(patches, tessellatePatches(patches, tess), tess);
        EXPECT_EQ(found, 0) << cage.name;
        EXPECT_GT(edges, 1000) << cage.name;
        EXPECT_GT(tJunctions(patches, tessellatePatches(patches, tess / 2), tess / 2).first, 0) << cage.name;
    }
}

}  // namespace
}  // namespace subdfit::render
