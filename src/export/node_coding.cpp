#include "export/node_coding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace subdfit::exporter {
namespace {

// A node of a T×T tile and the two coded nodes it is predicted from ((a, a) for the corners,
// which are predicted as the channel's center).
struct Prediction {
    int i, j;          // the node
    int ai, aj, bi, bj;  // its bracket
    float w;           // weight of b
    bool corner;
};

// The coding order of one tile: corners, then for s = the largest power of two below T down to
// 1, the odd multiples of s along u on the rows coded so far, then along v on every column.
std::vector<Prediction> codingOrder(int T) {
    std::vector<Prediction> order;
    for (int j : {0, T})
        for (int i : {0, T}) order.push_back({i, j, i, j, i, j, 0.0f, true});
    std::vector<bool> rowCoded(size_t(T) + 1, false), columnCoded(size_t(T) + 1, false);
    rowCoded[0] = rowCoded[size_t(T)] = columnCoded[0] = columnCoded[size_t(T)] = true;
    int s = 1;
    while (s * 2 < T) s *= 2;
    for (; s >= 1; s /= 2) {
        auto bracket = [&](int x) { return std::pair{x - s, std::min(x + s, T)}; };
        std::vector<int> fresh;  // odd multiples of s below T
        for (int x = s; x < T; x += 2 * s) fresh.push_back(x);
        for (int j = 0; j <= T; ++j) {
            if (!rowCoded[size_t(j)]) continue;
            for (int i : fresh) {
                const auto [a, b] = bracket(i);
                order.push_back({i, j, a, j, b, j, float(i - a) / float(b - a), false});
            }
        }
        for (int i : fresh) columnCoded[size_t(i)] = true;
        for (int j : fresh) {
            const auto [a, b] = bracket(j);
            for (int i = 0; i <= T; ++i)
                if (columnCoded[size_t(i)]) order.push_back({i, j, i, a, i, b, float(j - a) / float(b - a), false});
        }
        for (int j : fresh) rowCoded[size_t(j)] = true;
    }
    return order;
}

template <class Visit>
void forEachNode(const surface::TexelLayout& layout, Visit&& visit) {
    const auto order = codingOrder(layout.resolution);
    std::vector<bool> coded(size_t(layout.nodeCount), false);
    for (int face = 0; face < layout.ptexFaceCount; ++face)
        for (const Prediction& p : order) {
            const int node = layout.node(face, p.i, p.j);
            if (coded[size_t(node)]) continue;
            coded[size_t(node)] = true;
            visit(node, p.corner, layout.node(face, p.ai, p.aj), layout.node(face, p.bi, p.bj), p.w);
        }
}

}  // namespace

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
                 const ChannelQuantisation& q, ByteWriter& out) {
    std::vector<float> decoded(size_t(layout.nodeCount), 0.0f);
    forEachNode(layout, [&](int node, bool corner, int a, int b, float w) {
        const float predicted = corner ? q.center : (1.0f - w) * decoded[size_t(a)] + w * decoded[size_t(b)];
        const double residual = std::round((double(values[size_t(node) * size_t(stride) + size_t(channel)]) - predicted) / q.step);
        const auto r = std::int64_t(std::clamp(residual, -9.0e15, 9.0e15));
        out.putSigned(r);
        decoded[size_t(node)] = predicted + float(double(r) * q.step);
    });
}

void decodeNodes(const surface::TexelLayout& layout, std::span<float> values, int stride, int channel,
                 const ChannelQuantisation& q, ByteReader& in) {
    std::vector<float> decoded(size_t(layout.nodeCount), 0.0f);
    forEachNode(layout, [&](int node, bool corner, int a, int b, float w) {
        const float predicted = corner ? q.center : (1.0f - w) * decoded[size_t(a)] + w * decoded[size_t(b)];
        const float value = predicted + float(double(in.getSigned()) * q.step);
        if (!std::isfinite(value)) throw Error(in.what() + ": a map value is not finite");
        decoded[size_t(node)] = value;
        values[size_t(node) * size_t(stride) + size_t(channel)] = value;
    });
}

}  // namespace subdfit::exporter
