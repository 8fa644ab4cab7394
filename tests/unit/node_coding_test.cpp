// The map node coder (codec/node_coding.h): a smooth map's residuals are near zero, corners
// included, a noisy map is predicted by its mean rather than by its noisy neighbours, each
// level's residuals cost about their entropy, and a damaged level is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <zstd.h>

#include "codec/node_coding.h"
#include "limit_values.h"
#include "mesh/procedural.h"
#include "surface/tessellation.h"
#include "surface/texel_layout.h"

namespace subdfit::codec {
namespace {

constexpr int kResolution = 4;

// Unit Gaussian noise, one value per node of `layout`.
std::vector<float> unitNoise(const surface::TexelLayout& layout, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    std::vector<float> values(size_t(layout.nodeCount));
    for (float& v : values) v = noise(rng);
    return values;
}

struct Coded {
    std::vector<unsigned char> bytes;
    std::vector<float> decoded;
    // What the section stores of them: zstd at the writer's level.
    std::size_t packed() const {
        std::vector<char> frame(ZSTD_compressBound(bytes.size()));
        return ZSTD_compress(frame.data(), frame.size(), bytes.data(), bytes.size(), 19);
    }
};

Coded roundTrip(const surface::TexelLayout& layout, const std::vector<float>& values, const ChannelQuantisation& q) {
    ByteWriter out;
    encodeNodes(layout, values, 1, 0, q, out);
    Coded coded{out.bytes(), std::vector<float>(values.size())};
    ByteReader in(coded.bytes, "nodes");
    decodeNodes(layout, coded.decoded, 1, 0, q, in);
    EXPECT_EQ(in.remaining(), 0u);
    return coded;
}

TEST(NodeCoding, ASmoothMapFarFromItsMeanCostsUnderABitANode) {
    // Heights around 0.3 with one spike to 1.0: the range's center (0.65) is far from every
    // corner, which a prediction from the center would pay for at every shared corner
    // (residuals of ~-127 steps: 8 bits each at least).
    const auto cage = mesh::makeQuadSphere(4);
    const auto layout = surface::buildTexelLayout(cage, kResolution);
    auto values = test::valuesOnLimit(cage, layout, [](glm::vec3 p) { return 0.3f + 0.01f * p.x; });
    values[7] = 1.0f;
    const ChannelQuantisation q = quantisationFor(values, 1, 0, 8);
    const Coded coded = roundTrip(layout, values, q);
    EXPECT_EQ(coded.bytes[0] & 15, 8) << "the corners lean fully on their neighbours";
    EXPECT_EQ(coded.bytes[0] >> 4, 8) << "so do the interpolated nodes";
    EXPECT_LT(8.0 * double(coded.packed()), double(layout.nodeCount));
    for (size_t n = 0; n < values.size(); ++n)
        ASSERT_LE(std::abs(coded.decoded[n] - values[n]), 0.5f * q.step * 1.001f);
}

TEST(NodeCoding, NoiseIsPredictedByItsMean) {
    // Independent noise: a neighbour says nothing about a node, and leaning on it would add its
    // noise to every residual.
    const auto cage = mesh::makeQuadSphere(16);
    const auto layout = surface::buildTexelLayout(cage, kResolution);
    const std::vector<float> values = unitNoise(layout, 3);
    const ChannelQuantisation q = quantisationFor(values, 1, 0, 8);
    const Coded coded = roundTrip(layout, values, q);
    EXPECT_LE(coded.bytes[0] & 15, 2) << "corner lean, in eighths";
    EXPECT_LE(coded.bytes[0] >> 4, 4) << "interpolated lean, in eighths";
    // Unit Gaussian noise quantised at step q costs its differential entropy less log2(q),
    // log2(sqrt(2πe) / q) bits a value; the coder spends a few hundredths of a bit more, and
    // each level's probability table (a few hundred bytes for the ~250 symbols of 8 bits).
    const double entropy = std::log2(std::sqrt(2.0 * M_PI * M_E) / q.step);
    EXPECT_LT(8.0 * double(coded.packed()), (entropy + 0.15) * layout.nodeCount + 5 * 8 * 300);
    for (size_t n = 0; n < values.size(); ++n)
        ASSERT_LE(std::abs(coded.decoded[n] - values[n]), 0.5f * q.step * 1.001f);
}

TEST(NodeCoding, AnImpossibleLeanIsRefused) {
    const auto cage = mesh::makeQuadSphere(2);
    const auto layout = surface::buildTexelLayout(cage, kResolution);
    const std::vector<float> values(size_t(layout.nodeCount), 0.5f);
    const ChannelQuantisation q{.center = 0.5f, .step = 0.01f};
    ByteWriter out;
    encodeNodes(layout, values, 1, 0, q, out);
    std::vector<unsigned char> bytes = out.bytes();
    bytes[0] = 9;
    std::vector<float> decoded(values.size());
    ByteReader in(bytes, "nodes");
    EXPECT_THROW(decodeNodes(layout, decoded, 1, 0, q, in), Error);
}

TEST(NodeCoding, ADamagedLevelIsRefused) {
    // Noise: every pass entropy-coded (its varints would pack larger).
    const auto cage = mesh::makeQuadSphere(32);
    const auto layout = surface::buildTexelLayout(cage, kResolution);
    const std::vector<float> values = unitNoise(layout, 5);
    const ChannelQuantisation q = quantisationFor(values, 1, 0, 8);
    ByteWriter out;
    encodeNodes(layout, values, 1, 0, q, out);
    auto refusal = [&](std::vector<unsigned char> bytes) {
        std::vector<float> decoded(values.size());
        ByteReader in(bytes, "nodes");
        try {
            decodeNodes(layout, decoded, 1, 0, q, in);
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    // After the leans and the coarse passes (none), the mask of entropy-coded passes, then the
    // corners': their byte count (a varint) and Draco's coding, its method first.
    const std::vector<unsigned char> good = out.bytes();
    ASSERT_EQ(good[1], 0);
    ASSERT_EQ(good[2], 0x1f) << "five passes, every one entropy-coded";
    size_t method = 3;
    while (good[method] & 0x80) ++method;
    ++method;
    EXPECT_EQ(refusal(good), "");
    auto badMethod = good;
    badMethod[method] = 9;
    EXPECT_EQ(refusal(badMethod), "nodes: malformed residuals");
    auto sixthPass = good;
    sixthPass[2] = 0x3f;
    EXPECT_EQ(refusal(sixthPass), "nodes: residuals for passes it has not");
    auto truncated = good;
    truncated.pop_back();
    EXPECT_NE(refusal(truncated), "");
}

}  // namespace
}  // namespace subdfit::codec

namespace subdfit::codec {
namespace {

// Embedded coding: the levels down to a coarser lattice at a coarse step, refined at the end.
// The whole stream decodes every node within step/2; the stream cut where the coarse passes end
// decodes the coarse lattice within the coarse step's half and interpolates the rest; the
// refinement costs about the bits it adds.
TEST(NodeCoding, AnEmbeddedCodingsCoarsePassesDecodeOnTheirOwn) {
    constexpr int kFine = 8, kCoarse = 2;
    const auto cage = mesh::makeQuadSphere(3);
    const auto layout = surface::buildTexelLayout(cage, kFine);
    std::mt19937 rng(3);
    std::normal_distribution<float> noise(0.0f, 0.01f);
    const std::vector<float> values = test::valuesOnLimit(
        cage, layout, [&](glm::vec3 p) { return std::sin(3.0f * p.x) * std::cos(2.0f * p.y) + noise(rng); });
    ChannelQuantisation q = quantisationFor(values, 1, 0, 10);
    const Coded single = roundTrip(layout, values, q);
    q.coarsePasses = passesOfLattice(kFine, kCoarse);
    q.coarseShift = 4;             // the coarse levels at 6 bits
    ASSERT_EQ(q.coarsePasses, 3);  // the corners, u and v at s = 4
    ByteWriter out;
    std::vector<std::size_t> ends;
    encodeNodes(layout, values, 1, 0, q, out, &ends);
    ASSERT_EQ(ends.size(), size_t(passCount(kFine)) + 1);  // every level and the refinement

    std::vector<float> whole(values.size());
    ByteReader all(out.bytes(), "nodes");
    EXPECT_EQ(decodeNodes(layout, whole, 1, 0, q, all), passCount(kFine) + 1);
    for (size_t n = 0; n < values.size(); ++n) EXPECT_LE(std::abs(whole[n] - values[n]), 0.5001f * q.step) << n;

    std::vector<float> coarse(values.size());
    ByteReader cut(std::span(out.bytes()).first(ends[size_t(q.coarsePasses) - 1]), "nodes");
    EXPECT_EQ(decodeNodes(layout, coarse, 1, 0, q, cut, NodeStream::LevelBlocks, NodeEnding::Prefix), q.coarsePasses);
    const float coarseStep = std::ldexp(q.step, q.coarseShift);
    const int spacing = kFine / kCoarse;
    double offLattice = 0.0;
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (int j = 0; j <= kFine; ++j)
            for (int i = 0; i <= kFine; ++i) {
                const size_t n = size_t(layout.node(face, i, j));
                if (i % spacing == 0 && j % spacing == 0)
                    EXPECT_LE(std::abs(coarse[n] - values[n]), 0.5001f * coarseStep);
                else offLattice = std::max(offLattice, double(std::abs(coarse[n] - values[n])));
            }
    EXPECT_GT(offLattice, 0.5 * coarseStep) << "the finer nodes are interpolated, not coded";

    const Coded embedded{out.bytes(), whole};
    std::printf("single step %zu bytes, embedded %zu (coarse passes %zu raw)\n", single.packed(), embedded.packed(),
                ends[size_t(q.coarsePasses) - 1]);
    // The refinement re-codes the coarse nodes' last 4 bits: a few percent of the whole at most.
    EXPECT_LT(double(embedded.packed()), 1.10 * double(single.packed()));
}

// The coarse passes may hold other values (the best on the coarse lattice alone): the prefix
// decodes those, the whole stream the map's own.
TEST(NodeCoding, AnEmbeddedCodingsCoarsePassesMayHoldValuesOfTheirOwn) {
    constexpr int kFine = 4;
    const auto cage = mesh::makeQuadSphere(3);
    const auto layout = surface::buildTexelLayout(cage, kFine);
    const std::vector<float> values =
        test::valuesOnLimit(cage, layout, [](glm::vec3 p) { return std::sin(3.0f * p.x); });
    std::vector<float> coarseValues(values.size());
    for (size_t n = 0; n < values.size(); ++n) coarseValues[n] = values[n] + 0.05f;  // off by 0.05 everywhere
    ChannelQuantisation q = quantisationFor(values, 1, 0, 8);
    q.coarsePasses = passesOfLattice(kFine, 2);
    q.coarseShift = 2;
    ByteWriter out;
    std::vector<std::size_t> ends;
    encodeNodes(layout, values, 1, 0, q, out, &ends, coarseValues);
    std::vector<float> whole(values.size()), coarse(values.size());
    ByteReader all(out.bytes(), "nodes");
    decodeNodes(layout, whole, 1, 0, q, all);
    ByteReader cut(std::span(out.bytes()).first(ends[size_t(q.coarsePasses) - 1]), "nodes");
    ASSERT_EQ(decodeNodes(layout, coarse, 1, 0, q, cut, NodeStream::LevelBlocks, NodeEnding::Prefix), q.coarsePasses);
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (int j = 0; j <= kFine; j += 2)
            for (int i = 0; i <= kFine; i += 2) {
                const size_t n = size_t(layout.node(face, i, j));
                EXPECT_LE(std::abs(coarse[n] - coarseValues[n]), 0.5001f * std::ldexp(q.step, q.coarseShift)) << n;
            }
    for (size_t n = 0; n < values.size(); ++n) EXPECT_LE(std::abs(whole[n] - values[n]), 0.5001f * q.step) << n;
}

}  // namespace
}  // namespace subdfit::codec
