#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <glm/vec4.hpp>
#include <string>
#include <vector>

#include "io/image_header.h"

namespace subdfit::io {

// Writes an RGB image (rows bottom-up, as GL reads them) clamped to [0,1], 8-bit, format by
// extension (PNG, ...), atomically. Throws subdfit::Error naming the file on failure.
void writeImage(const std::filesystem::path& path, const std::vector<glm::vec4>& pixels, int width, int height);

// A line of text on an image: its top-left corner at pixel (x, y) counted from the image's
// top-left corner, `size` pixels tall (UTF-8).
struct ImageText {
    std::string text;
    int x = 0, y = 0;
    int size = 14;
    glm::vec4 colour{1.0f};
};

// writeImage with `texts` drawn over the pixels, anti-aliased, in DejaVu Sans (Debian's
// fonts-dejavu-core, through OpenImageIO and FreeType). Where the font cannot be found, the
// image is written without them and one warning says so: a caption is not worth a failed run.
void writeImage(const std::filesystem::path& path, const std::vector<glm::vec4>& pixels, int width, int height,
                const std::vector<ImageText>& texts);

// An image as 8-bit RGBA, top row first (as files store them).
struct DecodedImage {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;  // width × height × 4
};

// What an input image may cost. Its header is read before anything is decoded (a few hundred
// bytes of PNG or JPEG can promise 16384² pixels): it may state at most kMaxImagePixels (a 16K ×
// 8K texture), and at most kMaxWholeImagePixels where rows cannot stream (an interlaced PNG, a
// progressive JPEG, and every format but PNG and JPEG, which OpenImageIO decodes whole), and at
// most kMaxImageChannels channels. It is decoded at most kMaxDecodedSide on a side (larger ones
// smaller by a whole factor, as their rows stream), and the images one input file names share
// kMaxImagePixelsPerFile decoded pixels (four 4096² textures, 256 MiB as RGBA): past that, each
// is decoded smaller still, down to kSmallestBudgetedSide, then refused.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(1) << 27;
inline constexpr std::int64_t kMaxWholeImagePixels = std::int64_t(1) << 25;
inline constexpr int kMaxImageChannels = 16;
inline constexpr int kMaxDecodedSide = 4096;
inline constexpr std::int64_t kMaxImagePixelsPerFile = std::int64_t(1) << 26;
inline constexpr int kSmallestBudgetedSide = 256;

// What an image's header says, read without decoding it (PNG's, JPEG's, GIF's and WebP's by
// io/image_header.h, any other format's by OpenImageIO). Throws subdfit::Error naming
// `nameForErrors` for an unknown format, a corrupt header, or an image beyond the limits above.
ImageHeader readImageHeader(const void* data, std::size_t size, const std::string& nameForErrors);

// The decoded pixels the images of one input file may still take (kMaxImagePixelsPerFile in all).
class PixelBudget {
public:
    explicit PixelBudget(std::int64_t pixels = kMaxImagePixelsPerFile) : total_(pixels), left_(pixels) {}
    // The factor `image` is decoded smaller by, to fit kMaxDecodedSide and what is left, which it
    // then spends. Throws subdfit::Error naming `nameForErrors` when even an image reduced to
    // kSmallestBudgetedSide would not fit.
    int spend(const ImageHeader& image, const std::string& nameForErrors);

private:
    std::int64_t total_, left_;
};

// An image's header and the factor it is decoded smaller by on each side.
struct DecodePlan {
    ImageHeader header;
    int factor = 1;
};

// readImageHeader, and the factor: kMaxDecodedSide's, or `budget`'s (which it spends) when given.
DecodePlan planDecode(const void* data, std::size_t size, const std::string& nameForErrors,
                      PixelBudget* budget = nullptr);

// Decodes an image file's bytes (PNG, JPEG, WebP, BMP, GIF, TIFF, EXR: told apart by their first
// bytes) as `plan` says, grey or RGB made RGBA (alpha 1), 16-bit and float made 8-bit, row strip
// by row strip into the (reduced) RGBA result. Throws subdfit::Error naming `nameForErrors` for
// an unknown format, a corrupt or truncated image (a damaged JPEG's entropy-coded data is a
// warning: io/image_decoders.h), or running out of memory.
DecodedImage decodeImage(const void* data, std::size_t size, const std::string& nameForErrors, const DecodePlan& plan);

// planDecode, then decodeImage.
DecodedImage decodeImage(const void* data, std::size_t size, const std::string& nameForErrors,
                         PixelBudget* budget = nullptr);

// `image` resized (filtered: OpenImageIO's default for the ratio) to width × height.
DecodedImage resizedImage(const DecodedImage& image, int width, int height);

// `image` resized (filtered) to width × height and encoded as JPEG (at `quality`, 1..100;
// chroma halved unless `fullChroma`) or PNG: what a pipeline ships when it shrinks an asset's
// textures. Throws subdfit::Error.
enum class ImageFormat { Png, Jpeg };
std::vector<std::uint8_t> encodeImage(const DecodedImage& image, int width, int height, ImageFormat format,
                                      int quality = 85, bool fullChroma = false);

// readInputFile, then decodeImage.
DecodedImage readImage(const std::filesystem::path& path, PixelBudget* budget = nullptr);

}  // namespace subdfit::io
