#pragma once
// The size an image's header states, read without decoding a pixel: a reader checks it against
// what the image should be before spending memory on it, and a decoder without an image library
// (the web decoder, apps/web) hands the bytes on knowing their size.
#include <optional>
#include <span>

namespace subdfit::io {

struct ImageSize {
    int width = 0, height = 0;
    friend bool operator==(const ImageSize&, const ImageSize&) = default;
};

// A baseline or progressive JPEG's frame size (its first SOFn marker), or nothing when the bytes
// are not a JPEG whose markers lead to one.
std::optional<ImageSize> jpegSize(std::span<const unsigned char> bytes);

}  // namespace subdfit::io
