// The cage inside a .subd: Draco where it gives back the same cage and is smaller, plain
// otherwise, and always the same faces (renumbered, maybe rotated) as the correspondence says.
#include <gtest/gtest.h>

#include <algorithm>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "codec/byte_stream.h"
#include "codec/cage_coding.h"
#include "error_message.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "test_paths.h"

namespace subdfit::codec {
namespace {

constexpr int kBits = 14;

// Draco, its marks in pairs (coding 2) or once per edge (coding 3).
bool usesDraco(const CodedCage& coded) { return coded.bytes.at(0) == 2 || coded.bytes.at(0) == 3; }

// Every face of `cage` is the decoded face the correspondence names, corner for corner.
void expectSameFaces(const mesh::PolygonMesh& cage, const CodedCage& coded) {
    const auto& to = coded.correspondence;
    const auto& decoded = coded.decoded;
    ASSERT_EQ(decoded.faceCount(), cage.faceCount());
    ASSERT_EQ(decoded.vertexCount(), cage.vertexCount());
    std::vector<int> first(1, 0);
    for (int n : decoded.faceSizes) first.push_back(first.back() + n);
    for (int f = 0, at = 0; f < cage.faceCount(); at += cage.faceSizes[size_t(f)], ++f) {
        const int n = cage.faceSizes[size_t(f)], g = to.face[size_t(f)];
        ASSERT_EQ(decoded.faceSizes[size_t(g)], n);
        for (int k = 0; k < n; ++k)
            ASSERT_EQ(decoded.faceIndices[size_t(first[size_t(g)] + k)],
                      to.vertex[size_t(cage.faceIndices[size_t(at + (k + to.rotation[size_t(f)]) % n)])]);
    }
}

mesh::PolygonMesh shape(const char* name) { return mesh::loadMesh(test::assetPath(std::string("osd-shapes/") + name)); }

TEST(CageCoding, AnArtistCageGoesThroughDraco) {
    const auto cage = shape("catmark_pawn.obj");
    const auto coded = encodeCage(cage, kBits);
    EXPECT_TRUE(usesDraco(coded));
    expectSameFaces(cage, coded);
}

// A decimator can leave a face wound against its neighbours: two faces then share a directed
// edge, which must not send the cage down the plain path.
TEST(CageCoding, AFaceWoundTheOtherWayStillGoesThroughDraco) {
    auto cage = shape("catmark_bishop.obj");
    std::reverse(cage.faceIndices.begin(), cage.faceIndices.begin() + cage.faceSizes[0]);
    const auto coded = encodeCage(cage, kBits);
    EXPECT_TRUE(usesDraco(coded));
    expectSameFaces(cage, coded);
}

// A coarse grid that puts two vertices on one cell moves the later one to a free neighbouring
// cell: the cage still goes through Draco, every face the same, every vertex within one step
// and a half (per axis) of where it was.
TEST(CageCoding, TwoVerticesOnOneCellStillGoThroughDraco) {
    auto cage = shape("catmark_pawn.obj");
    constexpr int kCoarse = 8;
    glm::vec3 low(1e30f), high(-1e30f);
    for (const glm::vec3& p : cage.positions) low = glm::min(low, p), high = glm::max(high, p);
    const float step = std::max({high.x - low.x, high.y - low.y, high.z - low.z}) / float((1 << kCoarse) - 1);
    // Vertex 0's nearest other vertex brought onto it.
    size_t nearest = 1;
    for (size_t v = 1; v < cage.positions.size(); ++v)
        if (glm::distance(cage.positions[v], cage.positions[0]) <
            glm::distance(cage.positions[nearest], cage.positions[0]))
            nearest = v;
    cage.positions[nearest] = cage.positions[0];
    const auto coded = encodeCage(cage, kCoarse);
    EXPECT_TRUE(usesDraco(coded));
    expectSameFaces(cage, coded);
    float farthest = 0.0f;
    for (size_t v = 0; v < cage.positions.size(); ++v) {
        const glm::vec3 error =
            glm::abs(coded.decoded.positions[size_t(coded.correspondence.vertex[v])] - cage.positions[v]);
        farthest = std::max({farthest, error.x, error.y, error.z});
    }
    EXPECT_GT(farthest, 0.51f * step);  // one was moved
    EXPECT_LE(farthest, 1.51f * step);
}

// Where a coded cage's bytes go: the parts add up to about the section, positions cost more
// than Draco's connectivity, and two fewer bits a coordinate save about 6 bits a vertex.
TEST(CageCoding, TheBytesSplitIntoConnectivityPositionsMarksAndTags) {
    const auto cage = shape("catmark_pawn.obj");  // quads and triangles, no tags
    const CageByteParts parts = cageByteParts(cage, kBits);
    ASSERT_TRUE(parts.draco);
    const std::size_t sum = parts.connectivity + parts.positions + parts.polygonMarks + parts.tags;
    EXPECT_NEAR(double(sum), double(parts.stored), 0.15 * double(parts.stored) + 40.0);
    EXPECT_GT(parts.positions, parts.connectivity);
    EXPECT_GT(parts.polygonMarks, 0u);
    const CageByteParts coarser = cageByteParts(cage, kBits - 2);
    EXPECT_EQ(coarser.connectivity, parts.connectivity);
    EXPECT_NEAR(double(parts.positions - coarser.positions), 6.0 / 8.0 * cage.vertexCount(), 0.35 * cage.vertexCount());

    const auto plain = cageByteParts(shape("catmark_cube_creases1.obj"), kBits);
    EXPECT_FALSE(plain.draco);
    EXPECT_GT(plain.tags, 0u);  // its creases
    EXPECT_EQ(plain.polygonMarks, 0u);
}

// A quad's two Draco triangles are marked along its diagonal, the longer edge: a quad cage's
// marks cost a few bits a face, not a byte a triangle.
TEST(CageCoding, AQuadCagesMarksCostAFewBitsAFace) {
    const mesh::PolygonMesh sphere = mesh::makeQuadSphere(12);
    const auto coded = encodeCage(sphere, kBits);
    ASSERT_TRUE(usesDraco(coded));
    expectSameFaces(sphere, coded);
    const CageByteParts parts = cageByteParts(sphere, kBits);
    EXPECT_LT(double(parts.polygonMarks), sphere.faceCount() / 16.0) << sphere.faceCount() << " quads";
}

// A quad's diagonal is marked once, in the first of its triangles Draco lays: the second's
// symbol (nothing more) goes in a stream of nearly all zeros. Quads whose corners start anywhere
// (as a remesh leaves them) cost well under a bit a face, and a triangle cage keeps coding 2.
TEST(CageCoding, AQuadsDiagonalIsMarkedOnce) {
    mesh::PolygonMesh pawn = shape("catmark_pawn.obj");
    for (int f = 0, first = 0; f < pawn.faceCount(); first += pawn.faceSizes[size_t(f)], ++f) {
        const auto begin = pawn.faceIndices.begin() + first;
        std::rotate(begin, begin + (f * 7 % 5) % pawn.faceSizes[size_t(f)], begin + pawn.faceSizes[size_t(f)]);
    }
    const auto coded = encodeCage(pawn, kBits);
    ASSERT_EQ(coded.bytes.at(0), 3);
    expectSameFaces(pawn, coded);
    EXPECT_LT(double(cageByteParts(pawn, kBits).polygonMarks), pawn.faceCount() / 10.0);
    EXPECT_EQ(encodeCage(mesh::makeLumpySphere(4, 0.1f, 3), kBits).bytes.at(0), 2);  // all triangles
}

// Coding 3's marks as a hostile file might give them: more symbols than triangles, or a symbol
// naming an edge the triangle has not, is refused in one line naming the section.
TEST(CageCoding, MarksOnceThatDoNotFitTheTrianglesAreRefused) {
    const mesh::PolygonMesh pawn = shape("catmark_pawn.obj");
    const auto coded = encodeCage(pawn, kBits);
    ASSERT_EQ(coded.bytes.at(0), 3);
    // coding | vertices | faces | origin, extent, bits | Draco's size and bytes | the marks' count ...
    ByteReader header(coded.bytes, "cage");
    header.get<std::uint8_t>();
    header.getVarint();
    header.getVarint();
    header.take(4 * sizeof(float) + 1);
    header.take(header.getVarint());
    const std::size_t marks = coded.bytes.size() - header.remaining();
    ByteReader counted(std::span(coded.bytes).subspan(marks), "cage");
    const std::uint64_t fresh = counted.getVarint();
    const std::size_t symbols = marks + (coded.bytes.size() - marks - counted.remaining());
    const auto refusal = [](const std::vector<unsigned char>& bytes) {
        ByteReader in(bytes, "hostile.subd: CAGE section");
        return test::errorMessage([&] { decodeCage(in); });
    };
    std::size_t triangles = 0;
    for (int n : pawn.faceSizes) triangles += std::size_t(n - 2);
    ByteWriter tooMany;
    tooMany.putBytes(std::span(coded.bytes).first(marks));
    tooMany.putVarint(triangles + 1);
    tooMany.putBytes(std::span(coded.bytes).subspan(symbols));
    EXPECT_EQ(refusal(tooMany.bytes()), "hostile.subd: CAGE section: more polygon marks than triangles");
    // Every first symbol "its second open edge": some triangle has fewer than two.
    std::vector<unsigned char> named = coded.bytes;
    for (std::size_t k = symbols; k < symbols + (fresh + 3) / 4; ++k) named[k] = 0xaa;
    const std::string message = refusal(named);
    EXPECT_EQ(message.rfind("hostile.subd: CAGE section: ", 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(CageCoding, ACageOfAFewFacesStaysPlain) {
    const auto cage = shape("catmark_cube_creases1.obj");
    const auto coded = encodeCage(cage, kBits);
    EXPECT_FALSE(usesDraco(coded));
    expectSameFaces(cage, coded);
    EXPECT_EQ(coded.decoded.faceIndices, cage.faceIndices);
}

// Edgebreaker would cut a non-manifold edge apart; where the cut cannot be undone the plain
// coding keeps the cage as it is.
TEST(CageCoding, ANonManifoldCageKeepsItsFaces) {
    const auto cage = shape("catmark_nonman_edges.obj");
    const auto coded = encodeCage(cage, kBits);
    expectSameFaces(cage, coded);
}

}  // namespace
}  // namespace subdfit::codec
