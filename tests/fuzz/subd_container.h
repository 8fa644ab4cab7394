#pragma once
// Valid .subd containers around section contents a fuzzer chose, so that the section parsers
// (rather than the file's checksum) see the hostile bytes: current header, zstd frames with their
// content checksums, the file's XXH3 trailer.
#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "codec/byte_stream.h"
#include "codec/subd_format.h"
#include "util/hash.h"

namespace subdfit::fuzz {

using Bytes = std::vector<unsigned char>;

inline void putSection(codec::ByteWriter& file, const char* tag, const Bytes& raw) {
    ZSTD_CCtx* context = ZSTD_createCCtx();
    ZSTD_CCtx_setParameter(context, ZSTD_c_checksumFlag, 1);
    Bytes stored(ZSTD_compressBound(raw.size()));
    const size_t size = ZSTD_compress2(context, stored.data(), stored.size(), raw.data(), raw.size());
    ZSTD_freeCCtx(context);
    file.putBytes({reinterpret_cast<const unsigned char*>(tag), 4});
    file.put<uint32_t>(uint32_t(size));
    file.put<uint32_t>(uint32_t(raw.size()));
    file.putBytes({stored.data(), size});
}

inline Bytes container(const std::vector<std::pair<const char*, Bytes>>& sections, uint32_t decodeTriangles = 0) {
    codec::ByteWriter file;
    file.putBytes({reinterpret_cast<const unsigned char*>("SUBD"), 4});
    file.put<uint16_t>(codec::kSubdVersion);
    file.put<uint16_t>(0);
    file.put<uint32_t>(uint32_t(sections.size()));
    file.put<uint32_t>(decodeTriangles);
    for (const auto& [tag, raw] : sections) putSection(file, tag, raw);
    const auto& bytes = file.bytes();
    file.put<uint64_t>(hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    return std::move(file.bytes());
}

// `body` split at each 0xff into the raw contents of a CAGE section and the sections after it
// (`first` picks which: DISP, NORM, AUVS, BCOL, MTRG, NTEX, EMIS in turn from there).
inline Bytes sectionsFrom(unsigned char first, const Bytes& body, uint32_t decodeTriangles = 0) {
    static const char* tags[] = {"DISP", "NORM", "AUVS", "BCOL", "MTRG", "NTEX", "EMIS"};
    std::vector<std::pair<const char*, Bytes>> sections;
    auto from = body.begin();
    for (size_t k = 0; k < 8; ++k) {
        const auto split = std::find(from, body.end(), 0xff);
        sections.push_back({k == 0 ? "CAGE" : tags[(first + k - 1) % 7], Bytes(from, split)});
        if (split == body.end()) break;
        from = split + 1;
    }
    return container(sections, decodeTriangles);
}

}  // namespace subdfit::fuzz
