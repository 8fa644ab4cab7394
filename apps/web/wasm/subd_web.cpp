// The web decoder's entry points (WebAssembly exports): subdfit::web::decode (web_decode.h) behind
// a C interface that subd_core.mjs calls, each result kept alive until subd_free.
#include <emscripten/emscripten.h>

#include <cstdint>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <unordered_map>

#include "codec/decode_density.h"
#include "util/error.h"
#include "web_decode.h"

namespace {

using subdfit::web::Decoded;
using subdfit::web::Result;

std::string lastError;
std::unordered_map<const Result*, std::unique_ptr<Decoded>> live;  // until subd_free

}  // namespace

extern "C" {

// The decoded surface, or null with subd_error() saying why in one line. `triangles` 0: the
// default density; `name` (UTF-8) names the file in messages; `prefix` 1: the bytes are the
// file's first, as they arrive (codec::SubdEnding::Prefix).
EMSCRIPTEN_KEEPALIVE Result* subd_decode(const std::uint8_t* bytes, std::uint32_t size, double triangles,
                                         const char* name, std::uint32_t prefix) {
    try {
        if (!(triangles >= 0.0) || triangles > double(subdfit::codec::kMaxDecodeTriangles))
            throw subdfit::Error("invalid option: triangles: must be in 0.." +
                                 std::to_string(subdfit::codec::kMaxDecodeTriangles));
        auto decoded =
            subdfit::web::decode({bytes, size}, std::int64_t(triangles), name,
                                 prefix ? subdfit::codec::SubdEnding::Prefix : subdfit::codec::SubdEnding::Whole);
        Result* result = &decoded->result;
        live.emplace(result, std::move(decoded));
        return result;
    } catch (const std::bad_alloc&) {
        lastError = std::string(name) + ": out of memory (the web decoder stops at 2 GiB)";
    } catch (const std::exception& e) {
        lastError = e.what();
    }
    return nullptr;
}

EMSCRIPTEN_KEEPALIVE const char* subd_error() { return lastError.c_str(); }

EMSCRIPTEN_KEEPALIVE void subd_free(Result* result) { live.erase(result); }
}
