// The table cache hands back a cage's tables built once for its topology: the same as a fresh
// build, whatever the positions, and never another topology's (faces, tags or level apart); past
// its size, the least recently used leave first.
#include <gtest/gtest.h>

#include "mesh/procedural.h"
#include "subdiv/adaptive_tables.h"
#include "subdiv/patch_set.h"
#include "subdiv/table_cache.h"

namespace subdfit::subdiv {
namespace {

void expectSame(const PatchSet& a, const PatchSet& b) {
    EXPECT_EQ(a.pointCount, b.pointCount);
    EXPECT_EQ(a.stencilOffsets, b.stencilOffsets);
    EXPECT_EQ(a.stencilIndices, b.stencilIndices);
    EXPECT_EQ(a.stencilWeights, b.stencilWeights);
    EXPECT_EQ(a.patchInfo, b.patchInfo);
    EXPECT_EQ(a.patchCvIndices, b.patchCvIndices);
    EXPECT_EQ(a.faceVertexIndices, b.faceVertexIndices);
}

TEST(SubdivTableCache, OneTopologyIsBuiltOnceWhateverItsPositions) {
    mesh::PolygonMesh cage = mesh::makeQuadSphere(3);
    const auto first = cachedPatchSet(cage, {.isolationLevel = 2});
    for (auto& p : cage.positions) p *= 1.5f;
    const auto again = cachedPatchSet(cage, {.isolationLevel = 2});
    EXPECT_EQ(first.get(), again.get());
    expectSame(*again, buildPatchSet(cage, {.isolationLevel = 2}));
}

TEST(SubdivTableCache, AnotherLevelTagOrFaceIsAnotherEntry) {
    const mesh::PolygonMesh cage = mesh::makeQuadSphere(2);
    const auto plain = cachedPatchSet(cage, {.isolationLevel = 2});
    EXPECT_NE(cachedPatchSet(cage, {.isolationLevel = 3}).get(), plain.get());

    mesh::PolygonMesh creased = cage;
    creased.tags.creases.push_back({creased.faceIndices[0], creased.faceIndices[1], 10.0f});
    const auto withCrease = cachedPatchSet(creased, {.isolationLevel = 2});
    EXPECT_NE(withCrease.get(), plain.get());
    expectSame(*withCrease, buildPatchSet(creased, {.isolationLevel = 2}));

    mesh::PolygonMesh turned = cage;  // one face's corners in another order: another topology
    std::swap(turned.faceIndices[1], turned.faceIndices[3]);
    EXPECT_NE(cachedAdaptiveTables(turned, 3).get(), cachedAdaptiveTables(cage, 3).get());
}

TEST(SubdivTableCache, TheLeastRecentlyUsedLeaveFirst) {
    struct Weighed {
        long points;
    };
    TableCache<Weighed> cache(100, [](const Weighed& w) { return w.points; });
    int builds = 0;
    const auto get = [&](const mesh::PolygonMesh& cage, long points) {
        return cache.get(cage, 3, [&] {
            ++builds;
            return Weighed{points};
        });
    };
    const mesh::PolygonMesh light = mesh::makeQuadSphere(1), dense = mesh::makeQuadSphere(2),
                            other = mesh::makeQuadSphere(3);
    get(light, 10);
    get(dense, 60);
    get(light, 10);  // used again: now the more recent of the two
    EXPECT_EQ(builds, 2);
    get(other, 40);  // 110 points: the dense cage, used least recently, leaves, though the largest
    EXPECT_EQ(builds, 3);
    get(light, 10);
    EXPECT_EQ(builds, 3);
    get(dense, 60);
    EXPECT_EQ(builds, 4);
}

}  // namespace
}  // namespace subdfit::subdiv
