// The pairs of ptex faces that share a base vertex, and the hash G finds them by: every pair found
// with its index, no other pair found, and no face's slots more than half full or far to search.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "sge/face_pairs.h"

namespace subdfit::sge {
namespace {

struct Faces {
    std::vector<int> offsets{0}, vertices;
    int vertexCount = 0;
    void add(std::vector<int> face) {
        std::sort(face.begin(), face.end());
        vertices.insert(vertices.end(), face.begin(), face.end());
        offsets.push_back(int(vertices.size()));
        for (int v : face) vertexCount = std::max(vertexCount, v + 1);
    }
    int count() const { return int(offsets.size()) - 1; }
    bool share(int a, int b) const {
        std::vector<int> common;
        std::set_intersection(vertices.begin() + offsets[size_t(a)], vertices.begin() + offsets[size_t(a) + 1],
                              vertices.begin() + offsets[size_t(b)], vertices.begin() + offsets[size_t(b) + 1],
                              std::back_inserter(common));
        return !common.empty();
    }
};

// Faces of 16 base vertices each, as a patch's stencils reach them: a rows × rows grid of
// overlapping 4 × 4 windows, the neighbourhoods of a regular quad cage.
Faces windowGrid(int rows) {
    Faces faces;
    const int side = rows + 3;
    for (int y = 0; y < rows; ++y)
        for (int x = 0; x < rows; ++x) {
            std::vector<int> face;
            for (int j = 0; j < 4; ++j)
                for (int i = 0; i < 4; ++i) face.push_back((y + j) * side + x + i);
            faces.add(face);
        }
    return faces;
}

// Every pair found by G's search with its own index, and only those; each face's slots at most
// half full; and the mean search short (linear probing at half load: about 1.5 reads).
void expectHashedExactly(const Faces& faces) {
    const FacePairs pairs = findFacePairs(faces.offsets, faces.vertices, faces.vertexCount);
    ASSERT_EQ(pairs.first.size(), pairs.second.size());
    ASSERT_EQ(int(pairs.regions.size()), faces.count());
    size_t expected = 0, probes = 0;
    for (int a = 0; a < faces.count(); ++a)
        for (int b = a + 1; b < faces.count(); ++b) {
            const int k = findPair(pairs, a, b);
            if (!faces.share(a, b)) {
                EXPECT_EQ(k, -1) << a << ", " << b;
                continue;
            }
            ++expected;
            ASSERT_GE(k, 0) << a << ", " << b;
            EXPECT_EQ(pairs.first[size_t(k)], a);
            EXPECT_EQ(pairs.second[size_t(k)], b);
        }
    EXPECT_EQ(pairs.first.size(), expected);
    for (int a = 0; a < faces.count(); ++a) {
        const int firstSlot = pairs.regions[size_t(a)].x, bits = pairs.regions[size_t(a)].y;
        const std::uint32_t size = 1u << bits;
        int full = 0;
        for (std::uint32_t s = 0; s < size; ++s) {
            const int b = pairs.slots[size_t(firstSlot) + s].x;
            if (b < 0) continue;
            ++full;
            probes += 1 + ((s - pairSlotOf(b, bits)) & (size - 1));  // reads to reach it
        }
        EXPECT_LE(2 * full, int(size)) << "face " << a;
    }
    EXPECT_LT(double(probes) / double(std::max<size_t>(1, expected)), 2.0);
}

TEST(FacePairs, RegularNeighbourhoodsAreEachFoundInAReadOrTwo) { expectHashedExactly(windowGrid(12)); }

// A vertex of valence 200 (every face reaches it, each pair shares it), faces with no pair, and
// faces whose ids are far apart: the hash must not depend on ids being close.
TEST(FacePairs, HighValenceSparseIdsAndLoneFaces) {
    Faces faces;
    std::mt19937 random(7);
    for (int f = 0; f < 200; ++f) faces.add({0, 1 + f, 1 + (f + 1) % 200});
    for (int f = 0; f < 20; ++f) faces.add({1000 + 3 * f, 1001 + 3 * f, 1002 + 3 * f});  // share nothing
    for (int f = 0; f < 60; ++f) {
        std::uniform_int_distribution<int> vertex(2000, 2100);
        faces.add({vertex(random), vertex(random) + 200, vertex(random) + 400});
    }
    expectHashedExactly(faces);
}

TEST(FacePairs, NoFacesAndOneFace) {
    expectHashedExactly(Faces{});
    Faces one;
    one.add({0, 1, 2, 3});
    expectHashedExactly(one);
}

}  // namespace
}  // namespace subdfit::sge
