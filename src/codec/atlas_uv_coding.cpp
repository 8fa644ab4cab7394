#include "codec/atlas_uv_coding.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <unordered_map>

#include "surface/appearance_atlas.h"
#include "surface/texel_layout.h"
#include "util/error.h"

namespace subdfit::codec {
namespace {

constexpr std::int64_t kLimit = std::int64_t(1) << 40;  // far beyond any coordinate, far from overflow

using Q = std::array<std::int64_t, 2>;  // a quantised coordinate pair

Q operator+(Q a, Q b) { return {a[0] + b[0], a[1] + b[1]}; }
Q operator-(Q a, Q b) { return {a[0] - b[0], a[1] - b[1]}; }

std::int64_t floorDiv(std::int64_t a, std::int64_t n) { return a / n - (a % n != 0 && (a < 0) != (n < 0)); }

// Where every ptex corner's value lives: the values of corner point n are slots first[n] ..
// first[n + 1] − 1, and corner c of face f uses slot slotOf[4f + c].
struct ValueSlots {
    std::vector<size_t> first, slotOf;
};

// Visits every value once, in the order both sides code them, with a prediction from the values
// of its own cage face already visited; `code(face, corner, prediction)` returns the value.
// A quad's corners are predicted by the parallelogram of the other three (or a neighbour); an
// n-gon's sub-faces have their corner (0,0) at its vertices, (1,0) and (0,1) at its edges'
// midpoints and (1,1) at its centre, and inside a chart the coordinates there are the mean of
// its vertices' (the texture is about affine across a face), so its vertices come first, each
// from the one before or, on a triangle, by the parallelogram across an edge already coded.
template <class Code>
void walkValues(const mesh::PolygonMesh& cage, const ValueSlots& slots, Code code) {
    std::vector<std::optional<Q>> values(slots.first.back());
    Q last{0, 0};
    auto value = [&](int f, int k) -> std::optional<Q>& { return values[slots.slotOf[4 * size_t(f) + size_t(k)]]; };
    auto visit = [&](int f, int k, Q prediction) {
        std::optional<Q>& slot = value(f, k);
        if (!slot) last = *(slot = code(f, k, prediction));
    };
    // Each triangle's values along its edges, for the parallelogram across them.
    struct Wing {
        int a, b;  // the edge's cage vertices
        Q atA, atB, opposite;
    };
    std::unordered_map<std::uint64_t, Wing> wings;
    auto edgeKey = [](int a, int b) {
        return std::uint64_t(std::uint32_t(std::min(a, b))) << 32 | std::uint32_t(std::max(a, b));
    };
    int ptex = 0;
    size_t offset = 0;
    for (const int n : cage.faceSizes) {
        const int* ids = cage.faceIndices.data() + offset;
        offset += size_t(n);
        if (n == 4) {
            const int f = ptex++;
            for (int k = 0; k < 4; ++k) {
                const auto &previous = value(f, (k + 3) % 4), &next = value(f, (k + 1) % 4),
                           &opposite = value(f, (k + 2) % 4);
                visit(f, k,
                      previous && next && opposite ? *previous + *next - *opposite
                      : previous                   ? *previous
                      : next                       ? *next
                                                   : last);
            }
            continue;
        }
        const int first = ptex;
        ptex += n;
        auto vertex = [&](int i) -> const std::optional<Q>& { return value(first + (i % n + n) % n, 0); };
        auto id = [&](int i) { return ids[(i % n + n) % n]; };
        // A triangle's vertex whose two neighbours are known: the parallelogram over the edge
        // between them, when the triangle across it has the same values there (the same chart).
        auto acrossEdge = [&](int i) -> std::optional<Q> {
            if (n != 3 || !vertex(i - 1) || !vertex(i + 1)) return std::nullopt;
            const auto wing = wings.find(edgeKey(id(i - 1), id(i + 1)));
            if (wing == wings.end()) return std::nullopt;
            const Wing& w = wing->second;
            const bool aFirst = w.a == id(i - 1);
            if ((aFirst ? w.atA : w.atB) != *vertex(i - 1) || (aFirst ? w.atB : w.atA) != *vertex(i + 1))
                return std::nullopt;
            return *vertex(i - 1) + *vertex(i + 1) - w.opposite;
        };
        for (int i = 0; i < n; ++i) {
            const std::optional<Q> parallelogram = acrossEdge(i);
            visit(first + i, 0, parallelogram ? *parallelogram : vertex(i - 1) ? *vertex(i - 1) : last);
        }
        if (n == 3)
            for (int i = 0; i < 3; ++i)
                wings[edgeKey(id(i), id(i + 1))] = {id(i), id(i + 1), *vertex(i), *vertex(i + 1), *vertex(i + 2)};
        auto midpoint = [&](int i, int j) {
            const Q sum = *vertex(i) + *vertex(j);
            return Q{floorDiv(sum[0], 2), floorDiv(sum[1], 2)};
        };
        for (int i = 0; i < n; ++i) {
            visit(first + i, 1, midpoint(i, i + 1));
            visit(first + i, 3, midpoint(i - 1, i));
        }
        Q sum{0, 0};
        for (int i = 0; i < n; ++i) sum = sum + *vertex(i);
        for (int i = 0; i < n; ++i) visit(first + i, 2, {floorDiv(sum[0], n), floorDiv(sum[1], n)});
    }
}

}  // namespace

int atlasUvBits(int atlasSize) {
    int bits = 2;
    while ((1 << (bits - 2)) < atlasSize) ++bits;
    return std::min(bits, 24);
}

void writeAtlasUvs(const mesh::PolygonMesh& cage, const surface::AppearanceAtlas& atlas, ByteWriter& out) {
    const surface::TexelLayout points = surface::buildTexelLayout(cage, 1);
    SUBDFIT_CHECK(atlas.present() && atlas.cornerUvs.size() == 4 * size_t(points.ptexFaceCount));
    const int bits = atlasUvBits(atlas.size);
    const double scale = std::ldexp(1.0, bits);
    out.putVarint(std::uint64_t(atlas.size));
    out.put<std::uint8_t>(std::uint8_t(bits));
    auto quantised = [&](size_t corner) {
        const glm::vec2 uv = atlas.cornerUvs[corner];
        return Q{std::llround(double(uv.x) * scale), std::llround(double(uv.y) * scale)};
    };
    std::vector<std::vector<Q>> values(size_t(points.nodeCount));
    std::vector<size_t> index(atlas.cornerUvs.size());
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            const Q q = quantised(4 * size_t(f) + size_t(k));
            auto& list = values[size_t(surface::cornerPoint(points, f, k))];
            auto at = std::find(list.begin(), list.end(), q);
            if (at == list.end()) at = list.insert(list.end(), q);
            index[4 * size_t(f) + size_t(k)] = size_t(at - list.begin());
        }
    ValueSlots slots{{0}, {}};
    for (const auto& list : values) {
        out.putVarint(list.size());
        slots.first.push_back(slots.first.back() + list.size());
    }
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            const size_t node = size_t(surface::cornerPoint(points, f, k)), corner = 4 * size_t(f) + size_t(k);
            if (values[node].size() > 1) out.putVarint(index[corner]);
            slots.slotOf.push_back(slots.first[node] + index[corner]);
        }
    walkValues(cage, slots, [&](int f, int k, Q prediction) {
        const Q q = quantised(4 * size_t(f) + size_t(k)), residual = q - prediction;
        out.putSigned(residual[0]);
        out.putSigned(residual[1]);
        return q;
    });
}

surface::AppearanceAtlas readAtlasUvs(ByteReader& in, const mesh::PolygonMesh& cage) {
    const surface::TexelLayout points = surface::buildTexelLayout(cage, 1);
    surface::AppearanceAtlas atlas;
    const std::uint64_t size = in.getVarint();
    if (size < 2 || size > std::uint64_t(surface::kMaxAtlasSize))
        throw Error(in.what() + ": atlas size " + std::to_string(size) + " out of range");
    atlas.size = int(size);
    const int bits = in.get<std::uint8_t>();
    if (bits != atlasUvBits(atlas.size))
        throw Error(in.what() + ": " + std::to_string(bits) + " bits for an atlas of " + std::to_string(size));
    const size_t corners = 4 * size_t(points.ptexFaceCount);
    ValueSlots slots{{0}, {}};
    std::vector<size_t> counts(size_t(points.nodeCount));
    for (size_t& count : counts) {
        count = in.getVarint();
        if (count < 1 || count > corners) throw Error(in.what() + ": bad value count");
        slots.first.push_back(slots.first.back() + count);
        // Each corner adds at most one value, and each value takes at least two bytes: refused
        // before anything that large is allocated.
        if (slots.first.back() > corners || slots.first.back() > in.remaining() / 2)
            throw Error(in.what() + ": more values than corners or data");
    }
    slots.slotOf.reserve(corners);
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            const size_t node = size_t(surface::cornerPoint(points, f, k));
            size_t index = 0;
            if (counts[node] > 1) {
                index = in.getVarint();
                if (index >= counts[node]) throw Error(in.what() + ": corner index out of range");
            }
            slots.slotOf.push_back(slots.first[node] + index);
        }
    std::vector<Q> values(slots.first.back());
    walkValues(cage, slots, [&](int f, int k, Q prediction) {
        const Q residual{in.getSigned(), in.getSigned()};
        if (std::abs(residual[0]) > 4 * kLimit || std::abs(residual[1]) > 4 * kLimit)
            throw Error(in.what() + ": coordinates out of range");
        const Q q = prediction + residual;
        if (std::abs(q[0]) > kLimit || std::abs(q[1]) > kLimit) throw Error(in.what() + ": coordinates out of range");
        return values[slots.slotOf[4 * size_t(f) + size_t(k)]] = q;
    });
    const double step = std::ldexp(1.0, -bits);
    atlas.cornerUvs.resize(corners);
    for (size_t c = 0; c < corners; ++c) {
        const Q& q = values[slots.slotOf[c]];
        atlas.cornerUvs[c] = {float(double(q[0]) * step), float(double(q[1]) * step)};
    }
    return atlas;
}

}  // namespace subdfit::codec
