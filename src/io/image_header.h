#pragma once
// What an image's header states, read without decoding a pixel: a reader checks it against what
// the image should be (and what it may cost) before spending memory on it, and a decoder without
// an image library (the web decoder, apps/web) hands the bytes on knowing their size. JPEG's is
// read here without any library; io/image_io.h reads every format's (JPEG's through this).
#include <cstdint>
#include <optional>
#include <span>

namespace subdfit::io {

struct ImageHeader {
    int width = 0, height = 0;
    int channels = 0;  // colour components
    std::int64_t pixels() const { return std::int64_t(width) * std::int64_t(height); }
    friend bool operator==(const ImageHeader&, const ImageHeader&) = default;
};

// A baseline or progressive JPEG's frame header (its first SOFn marker), or nothing when the
// bytes are not a JPEG whose markers lead to one.
std::optional<ImageHeader> jpegHeader(std::span<const unsigned char> bytes);

}  // namespace subdfit::io
