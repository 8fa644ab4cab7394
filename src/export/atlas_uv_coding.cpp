#include "export/atlas_uv_coding.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "surface/appearance_atlas.h"
#include "surface/texel_layout.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

constexpr int kMostAtlasSize = 16384;

}  // namespace

int atlasUvBits(int atlasSize) {
    int bits = 4;
    while ((1 << (bits - 4)) < atlasSize) ++bits;
    return std::min(bits, 24);
}

void writeAtlasUvs(const mesh::PolygonMesh& cage, const surface::AppearanceAtlas& atlas, ByteWriter& out) {
    const surface::TexelLayout points = surface::buildTexelLayout(cage, 1);
    SUBDFIT_CHECK(atlas.present() && atlas.cornerUvs.size() == 4 * size_t(points.ptexFaceCount));
    const int bits = atlasUvBits(atlas.size);
    const double scale = std::ldexp(1.0, bits);
    out.putVarint(std::uint64_t(atlas.size));
    out.put<std::uint8_t>(std::uint8_t(bits));
    using Q = std::array<std::int64_t, 2>;
    std::vector<std::vector<Q>> values(size_t(points.nodeCount));
    std::vector<int> index(atlas.cornerUvs.size());
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            const glm::vec2 uv = atlas.cornerUvs[4 * size_t(f) + size_t(k)];
            const Q q{std::llround(double(uv.x) * scale), std::llround(double(uv.y) * scale)};
            auto& list = values[size_t(surface::cornerPoint(points, f, k))];
            auto at = std::find(list.begin(), list.end(), q);
            if (at == list.end()) at = list.insert(list.end(), q);
            index[4 * size_t(f) + size_t(k)] = int(at - list.begin());
        }
    for (const auto& list : values) out.putVarint(list.size());
    Q previous{0, 0};
    for (const auto& list : values)
        for (const Q& q : list) {
            out.putSigned(q[0] - previous[0]);
            out.putSigned(q[1] - previous[1]);
            previous = q;
        }
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k)
            if (values[size_t(surface::cornerPoint(points, f, k))].size() > 1) out.putVarint(std::uint64_t(index[4 * size_t(f) + size_t(k)]));
}

surface::AppearanceAtlas readAtlasUvs(ByteReader& in, const mesh::PolygonMesh& cage) {
    const surface::TexelLayout points = surface::buildTexelLayout(cage, 1);
    surface::AppearanceAtlas atlas;
    const std::uint64_t size = in.getVarint();
    if (size < 2 || size > kMostAtlasSize) throw Error(in.what() + ": atlas size " + std::to_string(size) + " out of range");
    atlas.size = int(size);
    const int bits = in.get<std::uint8_t>();
    if (bits != atlasUvBits(atlas.size)) throw Error(in.what() + ": " + std::to_string(bits) + " bits for an atlas of " + std::to_string(size));
    const double step = std::ldexp(1.0, -bits);
    std::vector<size_t> counts(size_t(points.nodeCount)), first(size_t(points.nodeCount) + 1, 0);
    for (size_t n = 0; n < counts.size(); ++n) {
        counts[n] = in.getVarint();
        if (counts[n] < 1 || counts[n] > 4 * size_t(points.ptexFaceCount)) throw Error(in.what() + ": bad value count");
        first[n + 1] = first[n] + counts[n];
    }
    // Each corner adds at most one value, and each value takes at least two bytes: refused before
    // anything that large is allocated.
    if (first.back() > 4 * size_t(points.ptexFaceCount) || first.back() > in.remaining() / 2)
        throw Error(in.what() + ": more values than corners or data");
    std::vector<glm::vec2> values(first.back());
    std::int64_t u = 0, v = 0;
    constexpr std::int64_t kLimit = std::int64_t(1) << 40;
    for (glm::vec2& value : values) {
        u += in.getSigned(), v += in.getSigned();
        if (std::abs(u) > kLimit || std::abs(v) > kLimit) throw Error(in.what() + ": coordinates out of range");
        value = {float(double(u) * step), float(double(v) * step)};
    }
    atlas.cornerUvs.resize(4 * size_t(points.ptexFaceCount));
    for (int f = 0; f < points.ptexFaceCount; ++f)
        for (int k = 0; k < 4; ++k) {
            const size_t node = size_t(surface::cornerPoint(points, f, k));
            size_t index = 0;
            if (counts[node] > 1) {
                index = in.getVarint();
                if (index >= counts[node]) throw Error(in.what() + ": corner index out of range");
            }
            atlas.cornerUvs[4 * size_t(f) + size_t(k)] = values[first[node] + index];
        }
    return atlas;
}

}  // namespace subdfit::exporter
