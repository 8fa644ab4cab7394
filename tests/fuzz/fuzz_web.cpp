// The web decoder's file input under libFuzzer: subdfit::web::decode (apps/web/wasm/web_decode.h),
// what the WebAssembly module runs on the bytes a page or decode.mjs hands it, built natively. Two
// ways: raw bytes (mostly stopped by the file's checksum), and 'S' + a byte for the density + bytes
// made into a valid container's sections (subd_container.h), so that the reader, the density's
// pricing, the tessellation and the material see hostile contents; raw bytes are read as a
// prefix too (the first bytes of a download). Every input must give a
// surface whose arrays are consistent, or one line of subdfit::Error naming the file.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "subd_container.h"
#include "util/error.h"
#include "web_decode.h"

namespace {

void decode(const subdfit::fuzz::Bytes& bytes, std::int64_t triangles,
            subdfit::codec::SubdEnding ending = subdfit::codec::SubdEnding::Whole) {
    try {
        const auto decoded = subdfit::web::decode(bytes, triangles, "fuzz.subd", ending);
        const subdfit::web::Result& r = decoded->result;
        if (r.indexCount % 3 != 0 || r.vertexCount == 0) std::abort();
        for (std::uint32_t k = 0; k < r.indexCount; ++k)
            if (r.indices[k] >= r.vertexCount) std::abort();
    } catch (const subdfit::Error& e) {
        const std::string what = e.what();
        if (what.rfind("fuzz.subd: ", 0) != 0 || what.find('\n') != std::string::npos) {
            std::fprintf(stderr, "not one line naming the file: %s\n", what.c_str());
            std::abort();
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > 2 && data[0] == 'S') {
        // Few triangles: the fuzzer explores the reader, not the tessellation's cost.
        decode(subdfit::fuzz::sectionsFrom(data[2], subdfit::fuzz::Bytes(data + 3, data + size)), 1 + data[1] * 16);
        return 0;
    }
    decode(subdfit::fuzz::Bytes(data, data + size), 1000);
    decode(subdfit::fuzz::Bytes(data, data + size), 1000, subdfit::codec::SubdEnding::Prefix);  // as it arrives
    return 0;
}
