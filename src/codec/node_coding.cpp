#include "codec/node_coding.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include <draco/compression/config/compression_shared.h>
#include <draco/compression/entropy/symbol_decoding.h>
#include <draco/compression/entropy/symbol_encoding.h>
#include <draco/core/decoder_buffer.h>
#include <draco/core/encoder_buffer.h>
#include <zstd.h>

namespace subdfit::codec {
namespace {

// A node of a T×T tile and the two coded nodes it is interpolated from ((a, a) for the
// corners, predicted from their neighbours instead: cornerPredictors).
struct Prediction {
    int i, j;            // the node
    int ai, aj, bi, bj;  // its bracket
    float w;             // weight of b
    bool corner;
    int pass;  // 0 the corners, then one per direction of each level
};

// The coding order of one tile, in passes: the corners, then for s = the largest power of two
// below T down to 1, the odd multiples of s along u on the rows coded so far, then along v on
// every column.
std::vector<Prediction> codingOrder(int T) {
    std::vector<Prediction> order;
    for (int j : {0, T})
        for (int i : {0, T}) order.push_back({i, j, i, j, i, j, 0.0f, true, 0});
    int pass = 0;
    std::vector<bool> rowCoded(size_t(T) + 1, false), columnCoded(size_t(T) + 1, false);
    rowCoded[0] = rowCoded[size_t(T)] = columnCoded[0] = columnCoded[size_t(T)] = true;
    int s = 1;
    while (s * 2 < T) s *= 2;
    for (; s >= 1; s /= 2) {
        auto bracket = [&](int x) { return std::pair{x - s, std::min(x + s, T)}; };
        std::vector<int> fresh;  // odd multiples of s below T
        for (int x = s; x < T; x += 2 * s) fresh.push_back(x);
        ++pass;
        for (int j = 0; j <= T; ++j) {
            if (!rowCoded[size_t(j)]) continue;
            for (int i : fresh) {
                const auto [a, b] = bracket(i);
                order.push_back({i, j, a, j, b, j, float(i - a) / float(b - a), false, pass});
            }
        }
        for (int i : fresh) columnCoded[size_t(i)] = true;
        ++pass;
        for (int j : fresh) {
            const auto [a, b] = bracket(j);
            for (int i = 0; i <= T; ++i)
                if (columnCoded[size_t(i)])
                    order.push_back({i, j, i, a, i, b, float(j - a) / float(b - a), false, pass});
        }
        for (int j : fresh) rowCoded[size_t(j)] = true;
    }
    return order;
}

// What a node is predicted from: the weighted sum of up to four decoded nodes, or, with none,
// the channel's center.
struct Predictors {
    std::array<int, 4> nodes{};
    std::array<float, 4> weights{};
    int count = 0;
    bool corner = false;  // a tile corner (else interpolated between two coded nodes)
    void add(int node, float weight) {
        nodes[size_t(count)] = node;
        weights[size_t(count++)] = weight;
    }
};

// A corner is predicted from what is already decoded around it: the mean of its coded tile
// neighbours one cell away (a neighbouring tile often coded the shared edge already), else of
// the tile's coded corners, else the center. Most corners are shared, and predicting them from
// the center cost a raw value each.
Predictors cornerPredictors(const surface::TexelLayout& layout, int face, int i, int j,
                            const std::vector<bool>& coded) {
    const int T = layout.resolution;
    Predictors p;
    p.corner = true;
    for (const auto& [ni, nj] : {std::pair{i == 0 ? 1 : T - 1, j}, std::pair{i, j == 0 ? 1 : T - 1}})
        if (const int n = layout.node(face, ni, nj); coded[size_t(n)]) p.add(n, 1.0f);
    if (p.count == 0)
        for (const int cj : {0, T})
            for (const int ci : {0, T})
                if (const int n = layout.node(face, ci, cj); coded[size_t(n)] && p.count < 4) p.add(n, 1.0f);
    for (int k = 0; k < p.count; ++k) p.weights[size_t(k)] = 1.0f / float(p.count);
    return p;
}

// Visits every node once, in coding order, with what it is predicted from and its pass.
template <class Visit>
void forEachNode(const surface::TexelLayout& layout, NodeStream stream, Visit&& visit) {
    const auto order = codingOrder(layout.resolution);
    std::vector<bool> coded(size_t(layout.nodeCount), false);
    auto code = [&](int face, const Prediction& p) {
        const int node = layout.node(face, p.i, p.j);
        if (coded[size_t(node)]) return;
        Predictors predictors;
        if (p.corner) {
            predictors = cornerPredictors(layout, face, p.i, p.j, coded);
        } else {
            predictors.add(layout.node(face, p.ai, p.aj), 1.0f - p.w);
            predictors.add(layout.node(face, p.bi, p.bj), p.w);
        }
        coded[size_t(node)] = true;
        visit(node, predictors, p.pass);
    };
    if (stream == NodeStream::TileVarints) {
        for (int face = 0; face < layout.ptexFaceCount; ++face)
            for (const Prediction& p : order) code(face, p);
        return;
    }
    for (size_t begin = 0; begin < order.size();) {  // a pass is a run of the tile's order
        size_t end = begin;
        while (end < order.size() && order[end].pass == order[begin].pass) ++end;
        for (int face = 0; face < layout.ptexFaceCount; ++face)
            for (size_t k = begin; k < end; ++k) code(face, order[k]);
        begin = end;
    }
}

std::uint32_t zigzag(std::int64_t r) { return std::uint32_t((std::uint64_t(r) << 1) ^ std::uint64_t(r >> 63)); }
std::int64_t unzigzag(std::uint32_t z) { return std::int64_t(z >> 1) ^ -std::int64_t(z & 1); }

// Each pass's residuals (zigzag-mapped) are either Draco's entropy coding of them or plain
// varints, which the section's zstd then packs: the varints where they pack smaller (a few dozen
// nodes, whose probability table costs more than it saves; packed alone as the section packs
// them, up to 64 KB, beyond which the tables are a small part). `varint mask` (bit p: pass p is
// entropy-coded) comes first; an entropy-coded pass is `varint n` and its n bytes, a plain one
// its count's varints.
double packedBytes(ByteWriter& varints) {
    const std::vector<unsigned char>& bytes = varints.bytes();
    if (bytes.size() > 65536) return double(bytes.size());
    // The section's own level where the choice is close (a small map); past 16 KB a fast level
    // makes the same choices at about half the time (docs/measurements.md).
    const int level = bytes.size() <= 16384 ? 19 : 3;
    std::vector<unsigned char> frame(ZSTD_compressBound(bytes.size()));
    const std::size_t packed = ZSTD_compress(frame.data(), frame.size(), bytes.data(), bytes.size(), level);
    return ZSTD_isError(packed) ? double(bytes.size()) : double(packed);
}

void putPasses(const std::vector<std::vector<std::uint32_t>>& passes, ByteWriter& out,
               std::vector<std::size_t>* passEnds) {
    std::vector<ByteWriter> plain(passes.size()), coded(passes.size());
    ByteWriter allPlain;
    std::uint64_t mask = 0;
    for (size_t p = 0; p < passes.size(); ++p) {
        for (const std::uint32_t z : passes[p]) plain[p].putVarint(z);
        allPlain.putBytes(plain[p].bytes());
        draco::EncoderBuffer symbols;
        if (!passes[p].empty() && !draco::EncodeSymbols(passes[p].data(), int(passes[p].size()), 1, nullptr, &symbols))
            throw Error("a map's residuals could not be entropy-coded");
        if (passes[p].empty() || packedBytes(plain[p]) <= double(symbols.size())) continue;
        mask |= std::uint64_t(1) << p;
        coded[p].putVarint(symbols.size());
        coded[p].putBytes({reinterpret_cast<const unsigned char*>(symbols.data()), symbols.size()});
    }
    // A small map's passes pack better together than apart: all plain where that is smaller.
    double mixed = 0.0;
    ByteWriter plainPasses;
    for (size_t p = 0; p < passes.size(); ++p)
        if (mask >> p & 1) mixed += double(coded[p].bytes().size());
        else plainPasses.putBytes(plain[p].bytes());
    if (packedBytes(allPlain) <= mixed + packedBytes(plainPasses)) mask = 0;
    out.putVarint(mask);
    for (size_t p = 0; p < passes.size(); ++p) {
        out.putBytes((mask >> p & 1 ? coded[p] : plain[p]).bytes());
        if (passEnds) passEnds->push_back(out.bytes().size());
    }
}

void getEntropyCoded(ByteReader& in, std::size_t count, std::uint32_t* symbols) {
    const std::uint64_t bytes = in.getVarint();
    if (bytes > in.remaining())
        throw TruncatedData(in.what() + ": a residual block of " + std::to_string(bytes) + " bytes exceeds the data");
    const auto block = in.take(std::size_t(bytes));
    draco::DecoderBuffer buffer;  // the symbols' coding as Draco's current bitstream writes it
    buffer.Init(reinterpret_cast<const char*>(block.data()), block.size(), draco::kDracoMeshBitstreamVersion);
    if (!draco::DecodeSymbols(std::uint32_t(count), 1, &buffer, symbols))
        throw Error(in.what() + ": malformed residuals");
    if (buffer.remaining_size() != 0) throw Error(in.what() + ": bytes left over in a level's residuals");
}

// One pass's residuals, appended to `symbols`.
void getPass(ByteReader& in, std::size_t count, bool entropyCoded, std::vector<std::uint32_t>& symbols) {
    const size_t at = symbols.size();
    if (entropyCoded) {
        if (count == 0) throw Error(in.what() + ": residuals for a level without nodes");
        symbols.resize(at + count);
        getEntropyCoded(in, count, symbols.data() + at);
        return;
    }
    for (size_t k = 0; k < count; ++k) {
        const std::uint64_t z = in.getVarint();
        if (z > std::numeric_limits<std::uint32_t>::max()) throw Error(in.what() + ": a residual out of range");
        symbols.push_back(std::uint32_t(z));
    }
}

// Every node's residual, level by level (`counts` the nodes of each pass), as far as the passes
// are wholly present: all of them, but where a Prefix ends early.
std::vector<std::uint32_t> getPasses(ByteReader& in, const std::vector<std::size_t>& counts, NodeEnding ending) {
    std::vector<std::uint32_t> symbols;
    try {
        const std::uint64_t mask = in.getVarint();
        if (counts.size() < 64 && (mask >> counts.size()) != 0)
            throw Error(in.what() + ": residuals for passes it has not");
        for (size_t p = 0; p < counts.size(); ++p) {
            const ByteReader passStart = in;
            const size_t decoded = symbols.size();
            try {
                getPass(in, counts[p], mask >> p & 1, symbols);
            } catch (const TruncatedData&) {
                if (ending == NodeEnding::Whole) throw;
                in = passStart;
                symbols.resize(decoded);
                break;
            }
        }
    } catch (const TruncatedData&) {
        if (ending == NodeEnding::Whole) throw;  // else not even the mask: no pass
    }
    return symbols;
}

// Predictions lean from the channel's center towards what the neighbours say by lean / kLeanSteps:
// fully on a smooth map, hardly on a noisy one, where the neighbours' own noise would double the
// residuals' spread.
constexpr int kLeanSteps = 8;
// The coarse passes' step is at most 2^16 fine steps (its shift and their count share a byte).
constexpr int kMostCoarseShift = 16;

// Where each level's pass lies in the stream of an embedded coding: the coarse passes, the pass
// that refines their nodes, then the finer passes (predicted from the refined values, so they
// cost what they would at one step).
struct StreamOrder {
    int coarsePasses = 0;  // 0: no refinement, the passes in level order
    int index(int pass) const { return coarsePasses > 0 && pass >= coarsePasses ? pass + 1 : pass; }
    int passes(int levels) const { return levels + (coarsePasses > 0 ? 1 : 0); }
};

struct Leans {
    int corner = kLeanSteps, interpolated = kLeanSteps;
};

float predicted(const Predictors& p, const std::vector<float>& decoded, float center, const Leans& leans) {
    if (p.count == 0) return center;
    float neighbours = 0.0f;
    for (int k = 0; k < p.count; ++k) neighbours += p.weights[size_t(k)] * decoded[size_t(p.nodes[size_t(k)])];
    const int lean = p.corner ? leans.corner : leans.interpolated;
    return center + float(lean) / float(kLeanSteps) * (neighbours - center);
}

// The leans that code the channel in the fewest bits, estimated on the original values (what
// the decoded ones are within half a step of), a residual r costing about log2(1 + |r|).
Leans chooseLeans(const surface::TexelLayout& layout, const std::vector<float>& original,
                  const ChannelQuantisation& q) {
    std::array<double, kLeanSteps + 1> cornerCost{}, interpolatedCost{};
    forEachNode(layout, NodeStream::LevelBlocks, [&](int node, const Predictors& from, int) {
        if (from.count == 0) return;
        auto& cost = from.corner ? cornerCost : interpolatedCost;
        for (int lean = 0; lean <= kLeanSteps; ++lean) {
            const float prediction = predicted(from, original, q.center, {lean, lean});
            cost[size_t(lean)] += std::log2(1.0 + std::abs(std::round((original[size_t(node)] - prediction) / q.step)));
        }
    });
    auto cheapest = [](const auto& cost) { return int(std::min_element(cost.begin(), cost.end()) - cost.begin()); };
    return {cheapest(cornerCost), cheapest(interpolatedCost)};
}

}  // namespace

int passCount(int resolution) { return codingOrder(resolution).back().pass + 1; }

int passesOfLattice(int resolution, int coarse) {
    SUBDFIT_CHECK(coarse >= 1 && resolution % coarse == 0 && std::has_single_bit(unsigned(resolution / coarse)));
    const int spacing = resolution / coarse;
    int s = 1;  // the first level's spacing, as codingOrder
    while (s * 2 < resolution) s *= 2;
    int passes = 1;
    for (; s >= spacing && s >= 1; s /= 2) passes += 2;
    return passes;
}

ChannelQuantisation quantisationFor(std::span<const float> values, int stride, int channel, int bits) {
    float low = std::numeric_limits<float>::infinity(), high = -low;
    for (size_t k = size_t(channel); k < values.size(); k += size_t(stride)) {
        low = std::min(low, values[k]);
        high = std::max(high, values[k]);
    }
    if (!(high > low)) return {.center = std::isfinite(low) ? low : 0.0f, .step = 1.0f};
    return {.center = 0.5f * (low + high), .step = (high - low) / float((1u << std::clamp(bits, 1, 24)) - 1u)};
}

void encodeNodes(const surface::TexelLayout& layout, std::span<const float> values, int stride, int channel,
                 const ChannelQuantisation& q, ByteWriter& out, std::vector<std::size_t>* passEnds,
                 std::span<const float> coarseValues) {
    SUBDFIT_CHECK(coarseValues.empty() || coarseValues.size() == size_t(layout.nodeCount));
    std::vector<float> original(size_t(layout.nodeCount));
    for (size_t n = 0; n < original.size(); ++n) original[n] = values[n * size_t(stride) + size_t(channel)];
    const Leans leans = q.cornerLean >= 0 ? Leans{q.cornerLean, q.interpolatedLean} : chooseLeans(layout, original, q);
    SUBDFIT_CHECK(leans.corner >= 0 && leans.corner <= kLeanSteps && leans.interpolated >= 0 &&
                  leans.interpolated <= kLeanSteps);
    const int levels = passCount(layout.resolution);
    SUBDFIT_CHECK(q.coarsePasses >= 0 && q.coarsePasses <= levels && q.coarsePasses < 16 && q.coarseShift >= 0 &&
                  q.coarseShift <= kMostCoarseShift);
    const bool embedded = q.coarsePasses > 0 && q.coarseShift > 0;
    out.put<std::uint8_t>(std::uint8_t(leans.corner | leans.interpolated << 4));
    out.put<std::uint8_t>(embedded ? std::uint8_t(q.coarsePasses << 4 | (q.coarseShift - 1)) : std::uint8_t(0));
    const StreamOrder order{embedded ? q.coarsePasses : 0};
    std::vector<std::vector<std::uint32_t>> passes(size_t(order.passes(levels)));
    std::vector<float> decoded(size_t(layout.nodeCount), 0.0f);
    std::vector<int> coarseNodes;  // in coding order, refined before the finer levels
    auto code = [&](int node, float target, float prediction, double step, std::vector<std::uint32_t>& pass) {
        const double residual = std::round((double(target) - prediction) / step);
        // A value within the range the step was made for is a few 2^24 steps from its prediction at most.
        if (!(std::abs(residual) < double(1u << 30)))
            throw Error("a map value lies far outside its quantisation range");
        pass.push_back(zigzag(std::int64_t(residual)));
        decoded[size_t(node)] = prediction + float(residual * step);
    };
    bool refined = !embedded;
    auto refine = [&] {
        for (const int node : coarseNodes)
            code(node, original[size_t(node)], decoded[size_t(node)], q.step, passes[size_t(q.coarsePasses)]);
        refined = true;
    };
    forEachNode(layout, NodeStream::LevelBlocks, [&](int node, const Predictors& from, int pass) {
        if (!refined && pass >= q.coarsePasses) refine();
        const bool coarse = embedded && pass < q.coarsePasses;
        if (coarse) coarseNodes.push_back(node);
        const float target = coarse && !coarseValues.empty() ? coarseValues[size_t(node)] : original[size_t(node)];
        code(node, target, predicted(from, decoded, q.center, leans),
             std::ldexp(double(q.step), coarse ? q.coarseShift : 0), passes[size_t(order.index(pass))]);
    });
    if (!refined) refine();
    putPasses(passes, out, passEnds);
}

int decodeNodes(const surface::TexelLayout& layout, std::span<float> values, int stride, int channel,
                const ChannelQuantisation& q, ByteReader& in, NodeStream stream, NodeEnding ending,
                ChannelQuantisation* coded) {
    SUBDFIT_CHECK(stream != NodeStream::TileVarints || ending == NodeEnding::Whole);
    const bool blocks = stream != NodeStream::TileVarints;
    const int levels = passCount(layout.resolution);
    Leans leans;
    int coarsePasses = 0, coarseShift = 0;
    if (ending == NodeEnding::Prefix && in.remaining() < 2) {
        in.take(in.remaining());
        return 0;  // the channel's head is not here: no pass
    }
    if (stream == NodeStream::LevelBlocks) {
        const auto packed = in.get<std::uint8_t>(), coarse = in.get<std::uint8_t>();
        leans = {packed & 15, packed >> 4};
        coarsePasses = coarse >> 4;
        coarseShift = coarse == 0 ? 0 : (coarse & 15) + 1;
        if (coarse != 0 && (coarsePasses == 0 || coarsePasses > levels))
            throw Error(in.what() + ": bad coarse passes (" + std::to_string(coarsePasses) + " of " +
                        std::to_string(levels) + ")");
    } else {
        leans.corner = in.get<std::uint8_t>();
        leans.interpolated = in.get<std::uint8_t>();
    }
    if (leans.corner > kLeanSteps || leans.interpolated > kLeanSteps) throw Error(in.what() + ": bad prediction lean");
    if (coded) {
        *coded = q;
        coded->coarsePasses = coarsePasses;
        coded->coarseShift = coarseShift;
        coded->cornerLean = leans.corner;
        coded->interpolatedLean = leans.interpolated;
    }
    const StreamOrder order{coarsePasses};
    const int passes = order.passes(levels);
    std::vector<std::uint32_t> residuals;  // level by level: every node's, in coding order
    int present = passes;                  // the passes whose residuals are here
    if (blocks) {
        std::vector<std::size_t> counts(size_t(passes), 0);
        forEachNode(layout, stream, [&](int, const Predictors&, int pass) {
            ++counts[size_t(order.index(pass))];
            if (pass < coarsePasses) ++counts[size_t(coarsePasses)];  // and refined
        });
        residuals = getPasses(in, counts, ending);
        std::size_t held = 0;
        for (present = 0; present < passes && held + counts[size_t(present)] <= residuals.size(); ++present)
            held += counts[size_t(present)];
    }
    size_t next = 0;
    std::vector<float> decoded(size_t(layout.nodeCount), 0.0f);
    std::vector<int> coarseNodes;
    const Leans interpolation;  // where a pass is missing: between the bracket, not towards the center
    auto set = [&](int node, float value) {
        if (!std::isfinite(value)) throw Error(in.what() + ": a map value is not finite");
        decoded[size_t(node)] = value;
        values[size_t(node) * size_t(stride) + size_t(channel)] = value;
    };
    bool refined = coarsePasses == 0;
    auto refine = [&] {
        if (coarsePasses < present)  // the refinement is here
            for (const int node : coarseNodes)
                set(node, decoded[size_t(node)] + float(double(unzigzag(residuals[next++])) * q.step));
        refined = true;
    };
    forEachNode(layout, stream, [&](int node, const Predictors& from, int pass) {
        if (!refined && pass >= coarsePasses) refine();
        const bool here = order.index(pass) < present;
        std::int64_t residual = 0;
        if (here) residual = blocks ? unzigzag(residuals[next++]) : in.getSigned();
        const bool coarse = pass < coarsePasses;
        if (coarse) coarseNodes.push_back(node);
        set(node, predicted(from, decoded, q.center, here ? leans : interpolation) +
                      float(std::ldexp(double(residual) * q.step, coarse ? coarseShift : 0)));
    });
    if (!refined) refine();
    return present;
}

std::vector<float> codedValues(const surface::TexelLayout& layout, std::span<const float> values, int stride,
                               int bits) {
    std::vector<float> decoded(values.size());
    for (int c = 0; c < stride; ++c) {
        const ChannelQuantisation q = quantisationFor(values, stride, c, bits);
        ByteWriter out;
        encodeNodes(layout, values, stride, c, q, out);
        ByteReader in(out.bytes(), "coded values");
        decodeNodes(layout, decoded, stride, c, q, in);
    }
    return decoded;
}

}  // namespace subdfit::codec
