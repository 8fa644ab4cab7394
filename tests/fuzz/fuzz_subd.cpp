// The .subd decoder under libFuzzer, three ways:
//  - raw bytes: any file decodes or throws subdfit::Error, never a crash or an allocation past
//    the fuzz run's limit (random bytes mostly stop at the checksum);
//  - 'S' + bytes: the bytes, split at each 0xff, become the raw contents of a CAGE section and
//    then of the sections after it (the second byte picks which: DISP, NORM, AUVS, BCOL, MTRG,
//    NTEX, EMIS in turn from there), wrapped in a valid container (subd_container.h), so the
//    section parsers themselves see hostile data;
//  - 'R' + bytes: a real file of a cage and maps built from the bytes, with one byte flipped
//    where the input says: refused, or, if the flip changed nothing, decoded as encoded; and the
//    good file cut there, read as a prefix: decoded wherever its cage is whole.
// Every input is read both whole and as a prefix (codec::SubdEnding).
#include <zstd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "codec/subd_format.h"
#include "mesh/procedural.h"
#include "subd_container.h"
#include "util/error.h"

namespace {

using subdfit::fuzz::Bytes;

void decode(const Bytes& bytes) {
    for (const auto ending : {subdfit::codec::SubdEnding::Whole, subdfit::codec::SubdEnding::Prefix}) try {
            (void)subdfit::codec::decodeSubd(bytes, "fuzz.subd", nullptr, {}, ending);
        } catch (const subdfit::Error&) {}
}

// Where the cage's section ends in a file encodeSubd wrote (its first section).
size_t cageEnd(const Bytes& file) {
    uint32_t stored;
    std::memcpy(&stored, file.data() + 20, 4);
    return 16 + 12 + size_t(stored);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > 1 && data[0] == 'S') {
        decode(subdfit::fuzz::sectionsFrom(data[1], Bytes(data + 2, data + size)));
        return 0;
    }
    if (size >= 7 && data[0] == 'R') {
        const auto cage = subdfit::mesh::makeQuadSphere(1 + data[1] % 3);
        subdfit::surface::SurfaceMaps maps;
        maps.layout = subdfit::surface::buildTexelLayout(cage, 1 + data[2] % 4);
        for (int n = 0; n < maps.layout.nodeCount; ++n)
            maps.displacement.push_back(float(data[6 + size_t(n) % (size - 6)]) / 100.0f);
        // Laid out on the cage as it decodes, as every asset encodeSubd is given (shippableAsset).
        const subdfit::codec::SubdAsset asset = subdfit::codec::shippableAsset(cage, maps);
        const Bytes good = subdfit::codec::encodeSubd(asset);
        Bytes bad = good;
        uint32_t where;
        std::memcpy(&where, data + 2, 4);
        bad[where % bad.size()] ^= static_cast<unsigned char>(1 + where / bad.size() % 255);
        try {
            const auto read = subdfit::codec::decodeSubd(bad, "flipped.subd");
            if (read.cage.positions.size() != asset.cage.positions.size()) std::abort();  // a flip was read as data
        } catch (const subdfit::Error&) {}
        const size_t cut = where % (good.size() + 1);
        try {
            const auto read = subdfit::codec::decodeSubd(std::span(good).first(cut), "cut.subd", nullptr, {},
                                                         subdfit::codec::SubdEnding::Prefix);
            if (read.cage.positions.size() != asset.cage.positions.size()) std::abort();
        } catch (const subdfit::Error&) {
            if (cut >= cageEnd(good)) std::abort();  // a good file's prefix past its cage decodes
        }
        return 0;
    }
    decode(Bytes(data, data + size));
    return 0;
}
