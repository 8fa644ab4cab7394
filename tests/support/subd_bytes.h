#pragma once
// Raw .subd section contents made by hand, for tests and the hostile-file generator: what the
// encoder would never write (a cage far larger than its bytes suggest, repeated creases).
#include <array>
#include <cstdint>
#include <vector>

#include "codec/byte_stream.h"

#include <zstd.h>

namespace subdfit::test {

// `raw` as one zstd frame with a checksum of its content, as version-7 sections are stored.
inline std::vector<unsigned char> checksummedFrame(const std::vector<unsigned char>& raw) {
    ZSTD_CCtx* context = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(context, ZSTD_c_checksumFlag, 1);
    std::vector<unsigned char> frame(ZSTD_compressBound(raw.size()));
    frame.resize(ZSTD_compress2(context, frame.data(), frame.size(), raw.data(), raw.size()));
    ZSTD_freeCCtx(context);
    return frame;
}

// The raw CAGE section of an n × n quad grid over [−1, 1]² (z = 0), plain coded (a regular grid
// compresses to almost nothing), boundary "edge and corner" (with "none" a grid's border faces
// have no surface), with `creases` as (v0, v1) pairs of sharpness 2.
inline std::vector<unsigned char> plainGridCage(int n, const std::vector<std::array<int, 2>>& creases = {}) {
    codec::ByteWriter out;
    const int side = n + 1;
    out.put<std::uint8_t>(0);
    out.putVarint(std::uint64_t(side) * std::uint64_t(side));
    out.putVarint(std::uint64_t(n) * std::uint64_t(n));
    for (float c : {-1.0f, -1.0f, 0.0f, 2.0f}) out.put<float>(c);
    out.put<std::uint8_t>(16);
    for (int axis = 0; axis < 3; ++axis)
        for (int j = 0; j < side; ++j)
            for (int i = 0; i < side; ++i)
                out.put<std::uint16_t>(axis == 0   ? std::uint16_t(i * 65535 / n)
                                       : axis == 1 ? std::uint16_t(j * 65535 / n)
                                                   : 0);
    for (int f = 0; f < n * n; ++f) out.putVarint(4);
    std::int64_t previous = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
            for (int index : {j * side + i, j * side + i + 1, (j + 1) * side + i + 1, (j + 1) * side + i}) {
                out.putSigned(index - previous);
                previous = index;
            }
    out.put<std::uint8_t>(1);
    for (int k = 0; k < 3; ++k) out.put<std::uint8_t>(0);
    out.putVarint(creases.size());
    for (const auto& [a, b] : creases) {
        out.putVarint(std::uint64_t(a));
        out.putVarint(std::uint64_t(b));
        out.put<float>(2.0f);
    }
    out.putVarint(0);  // corners
    out.putVarint(0);  // holes
    return std::move(out.bytes());
}

}  // namespace subdfit::test
