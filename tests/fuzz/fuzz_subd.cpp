// The .subd decoder under libFuzzer, three ways:
//  - raw bytes: any file decodes or throws subdfit::Error, never a crash or an allocation past
//    the fuzz run's limit (random bytes mostly stop at the checksum);
//  - 'S' + bytes: the bytes, split at each 0xff, become the raw contents of a CAGE section and
//    then of the sections after it (the second byte picks which: DISP, NORM, AUVS, BCOL, MTRG,
//    NTEX, EMIS in turn from there), wrapped in valid zstd frames, a current header and a valid
//    checksum, so the section parsers themselves see hostile data;
//  - 'R' + bytes: a real file of a cage and maps built from the bytes, with one byte flipped
//    where the input says: refused, or, if the flip changed nothing, decoded as encoded.
#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "export/byte_stream.h"
#include "export/subd_format.h"
#include "mesh/procedural.h"
#include "util/error.h"
#include "util/hash.h"

namespace {

using Bytes = std::vector<unsigned char>;

void putSection(subdfit::exporter::ByteWriter& file, const char* tag, const Bytes& raw) {
    Bytes stored(ZSTD_compressBound(raw.size()));
    const size_t size = ZSTD_compress(stored.data(), stored.size(), raw.data(), raw.size(), 1);
    file.putBytes({reinterpret_cast<const unsigned char*>(tag), 4});
    file.put<uint32_t>(uint32_t(size));
    file.put<uint32_t>(uint32_t(raw.size()));
    file.putBytes({stored.data(), size});
}

Bytes container(const std::vector<std::pair<const char*, Bytes>>& sections) {
    subdfit::exporter::ByteWriter file;
    file.putBytes({reinterpret_cast<const unsigned char*>("SUBD"), 4});
    file.put<uint16_t>(subdfit::exporter::kSubdVersion);
    file.put<uint16_t>(0);
    file.put<uint32_t>(uint32_t(sections.size()));
    file.put<uint32_t>(0);  // decode triangles
    for (const auto& [tag, raw] : sections) putSection(file, tag, raw);
    const auto& bytes = file.bytes();
    file.put<uint64_t>(subdfit::hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    return std::move(file.bytes());
}

void decode(const Bytes& bytes) {
    try {
        (void)subdfit::exporter::decodeSubd(bytes, "fuzz.subd");
    } catch (const subdfit::Error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > 1 && data[0] == 'S') {
        static const char* tags[] = {"DISP", "NORM", "AUVS", "BCOL", "MTRG", "NTEX", "EMIS"};
        const Bytes body(data + 2, data + size);
        std::vector<std::pair<const char*, Bytes>> sections;
        auto from = body.begin();
        for (size_t k = 0; k < 8; ++k) {
            const auto split = std::find(from, body.end(), 0xff);
            sections.push_back({k == 0 ? "CAGE" : tags[(data[1] + k - 1) % 7], Bytes(from, split)});
            if (split == body.end()) break;
            from = split + 1;
        }
        decode(container(sections));
        return 0;
    }
    if (size >= 7 && data[0] == 'R') {
        subdfit::exporter::SubdAsset asset{.cage = subdfit::mesh::makeQuadSphere(1 + data[1] % 3), .maps = {}};
        asset.maps.layout = subdfit::surface::buildTexelLayout(asset.cage, 1 + data[2] % 4);
        for (int n = 0; n < asset.maps.layout.nodeCount; ++n)
            asset.maps.displacement.push_back(float(data[6 + size_t(n) % (size - 6)]) / 100.0f);
        const Bytes good = subdfit::exporter::encodeSubd(asset);
        Bytes bad = good;
        uint32_t where;
        std::memcpy(&where, data + 2, 4);
        bad[where % bad.size()] ^= static_cast<unsigned char>(1 + where / bad.size() % 255);
        try {
            const auto read = subdfit::exporter::decodeSubd(bad, "flipped.subd");
            if (read.cage.positions.size() != asset.cage.positions.size()) std::abort();  // a flip was read as data
        } catch (const subdfit::Error&) {
        }
        return 0;
    }
    decode(Bytes(data, data + size));
    return 0;
}
