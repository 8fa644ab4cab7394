#pragma once
// What an image's header states, read without decoding a pixel: a reader checks it against what
// the image should be (and what it may cost) before spending memory on it, and a decoder without
// an image library (the web decoder, apps/web) hands the bytes on knowing their size. PNG's,
// JPEG's, GIF's and WebP's are read here without any library, so that no library ever allocates
// what a forged header states; io/image_io.h reads every other format's with OpenImageIO.
#include <cstdint>
#include <optional>
#include <span>
#include <string>

namespace subdfit::io {

struct ImageHeader {
    int width = 0, height = 0;
    int channels = 0;  // colour components
    // Rows not stored in order (an Adam7 PNG, a progressive JPEG): a decoder holds the whole
    // image (or its coefficients) before the first row is done.
    bool interlaced = false;
    std::int64_t pixels() const { return std::int64_t(width) * std::int64_t(height); }
    friend bool operator==(const ImageHeader&, const ImageHeader&) = default;
};

// A baseline or progressive JPEG's frame header (its first SOFn marker), or nothing when the
// bytes are not a JPEG whose markers lead to one.
std::optional<ImageHeader> jpegHeader(std::span<const unsigned char> bytes);

// Why a JPEG's marker structure is not one every decoder reads alike ("" when it is): SOI, then
// well-formed segments up to EOI: quantisation and Huffman tables that are sound (libjpeg's own
// tests), one 8-bit baseline, extended or progressive Huffman frame, scans whose components and
// tables exist and whose progression is valid, only the markers libjpeg knows. The entropy-coded
// data is not decoded: a decoder draws damage there as well as it can. The shipped asset's
// images are checked with this before any decoder sees them (codec/subd_format.h), so that
// `subdfit decode` (libjpeg) and the web decoder (the browser's) refuse the same files.
std::string jpegStructureProblem(std::span<const unsigned char> bytes);

// A PNG's IHDR, a GIF's logical screen, a WebP's VP8, VP8L or VP8X header; nothing when the bytes
// are not that format or its header is cut short.
std::optional<ImageHeader> pngHeader(std::span<const unsigned char> bytes);
std::optional<ImageHeader> gifHeader(std::span<const unsigned char> bytes);
std::optional<ImageHeader> webpHeader(std::span<const unsigned char> bytes);

}  // namespace subdfit::io
