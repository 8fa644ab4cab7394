// The budget search's cages, built on threads of their own (one or several rungs at once), are
// the cages built in turn, each prepared there before it is handed over.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

#include "mesh/procedural.h"
#include "simplify/cage/cage_ladder.h"
#include "simplify/cage/initial_cage.h"
#include "util/interrupt.h"

namespace subdfit::simplify {
namespace {

void expectTheCagesASourceBuildsInTurn(unsigned builders) {
    const mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.15f, 5);
    const std::vector<int> counts{400, 250, 160, 2};  // the last: too few faces survive decimation
    CageLadder ladder(reference, counts, CageShape::Triangles, {}, builders);
    const CageSource source(reference, true, counts.front());
    for (size_t k = 0; k + 1 < counts.size(); ++k) {
        const std::optional<mesh::PolygonMesh> cage = ladder.take(k);
        ASSERT_TRUE(cage.has_value()) << counts[k];
        const mesh::PolygonMesh expected = source.cage({.faces = counts[k]});
        EXPECT_EQ(cage->faceIndices, expected.faceIndices) << counts[k] << " faces, " << builders << " builders";
        EXPECT_EQ(cage->positions, expected.positions) << counts[k] << " faces, " << builders << " builders";
    }
    EXPECT_FALSE(ladder.take(counts.size() - 1).has_value());
    EXPECT_EQ(ladder.source().cage({.faces = 160}).positions, source.cage({.faces = 160}).positions);
}

TEST(CageLadder, GivesTheCagesASourceBuildsInTurn) { expectTheCagesASourceBuildsInTurn(1); }

TEST(CageLadder, SeveralBuildersGiveTheSameCages) { expectTheCagesASourceBuildsInTurn(3); }

TEST(CageLadder, PreparesEachCageBeforeHandingItOver) {
    const mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.15f, 5);
    std::mutex mutex;
    std::vector<int> prepared;  // on a builder's thread, before each cage is handed over
    CageLadder ladder(
        reference, {400, 160}, CageShape::Triangles,
        [&](const mesh::PolygonMesh& cage) {
            const std::lock_guard lock(mutex);
            prepared.push_back(cage.faceCount());
        },
        2);
    for (size_t k = 0; k < 2; ++k) {
        const std::optional<mesh::PolygonMesh> cage = ladder.take(k);
        ASSERT_TRUE(cage.has_value());
        const std::lock_guard lock(mutex);
        EXPECT_NE(std::find(prepared.begin(), prepared.end(), cage->faceCount()), prepared.end()) << cage->faceCount();
    }
}

// Prepared cages' tables fill the caches the judge reads from, so the builder keeps only
// kRunAhead rungs past those taken; a ladder left part way, or asked for its source, still ends.
TEST(CageLadder, BuildsOnlyKRunAheadRungsPastThoseTaken) {
    const mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.15f, 5);
    const std::vector<int> counts{400, 300, 250, 200, 160, 120};
    std::mutex mutex;
    std::vector<int> prepared;
    const auto preparedCount = [&] {
        const std::lock_guard lock(mutex);
        return prepared.size();
    };
    // Waits (up to a minute, for a loaded machine) until `n` cages are prepared.
    const auto waitFor = [&](size_t n) {
        for (int tries = 0; tries < 6000 && preparedCount() < n; ++tries)
            std::this_thread::sleep_for(std::chrono::milliseconds(10));
        return preparedCount();
    };
    {
        CageLadder ladder(
            reference, counts, CageShape::Triangles,
            [&](const mesh::PolygonMesh& cage) {
                const std::lock_guard lock(mutex);
                prepared.push_back(cage.faceCount());
            },
            1);
        ASSERT_TRUE(ladder.take(0).has_value());
        const size_t allowed = 1 + CageLadder::kRunAhead;
        ASSERT_EQ(waitFor(allowed), allowed);
        std::this_thread::sleep_for(std::chrono::milliseconds(300));  // time enough to build one more
        EXPECT_EQ(preparedCount(), allowed) << "the builder ran past kRunAhead";
        ASSERT_TRUE(ladder.take(1).has_value());
        EXPECT_EQ(waitFor(allowed + 1), allowed + 1) << "taking a rung lets the next be built";
    }  // left part way: the builder, waiting, is let go
    EXPECT_LT(preparedCount(), counts.size());

    prepared.clear();
    CageLadder whole(reference, counts, CageShape::Triangles, [&](const mesh::PolygonMesh& cage) {
        const std::lock_guard lock(mutex);
        prepared.push_back(cage.faceCount());
    });
    ASSERT_TRUE(whole.take(0).has_value());
    whole.source();  // builds every rung, taken or not
    EXPECT_EQ(preparedCount(), counts.size());
}

TEST(CageLadder, AStopRequestReachesTheCageWaitedFor) {
    const mesh::PolygonMesh reference = mesh::makeLumpySphere(4, 0.15f, 5);
    stopRequest() = true;
    CageLadder ladder(reference, {400, 160, 100}, CageShape::Triangles, {}, 2);
    EXPECT_THROW(ladder.take(0), Interrupted);
    EXPECT_THROW(ladder.take(2), Error);  // never begun, or interrupted: either way not waited for forever
    stopRequest() = false;
}

}  // namespace
}  // namespace subdfit::simplify
