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

// The most pixels an input image may have, and all the images one input file names together: a
// 16K × 8K texture, or eight 4K ones (512 MiB as 8-bit RGBA). A few hundred bytes of PNG or JPEG
// can promise 16384² pixels; the header says so before anything is decoded.
inline constexpr std::int64_t kMaxImagePixels = std::int64_t(1) << 27;
inline constexpr std::int64_t kMaxImagePixelsPerFile = kMaxImagePixels;

// What an image's header says, read without decoding it (a JPEG's by io::jpegHeader, any other
// format's by OpenImageIO). Throws subdfit::Error naming `nameForErrors` for an unknown format, a
// corrupt header, or an image of more than kMaxImagePixels pixels.
ImageHeader readImageHeader(const void* data, std::size_t size, const std::string& nameForErrors);

// The pixels the images of one input file may still take (kMaxImagePixelsPerFile in all).
class PixelBudget {
public:
    explicit PixelBudget(std::int64_t pixels = kMaxImagePixelsPerFile) : total_(pixels), left_(pixels) {}
    // Throws subdfit::Error naming `nameForErrors` when `image` does not fit what is left.
    void spend(const ImageHeader& image, const std::string& nameForErrors);

private:
    std::int64_t total_, left_;
};

// Decodes an image file's bytes (PNG, JPEG, WebP, BMP, TIFF, ...: what OpenImageIO reads, told
// apart by their first bytes), grey or RGB made RGBA (alpha 1), 16-bit and float made 8-bit,
// row strip by row strip into the RGBA buffer (no second copy of the image). Its header is
// checked first (readImageHeader; against `budget` when given). Throws subdfit::Error naming
// `nameForErrors` for an unknown format, a corrupt or truncated image, or too many pixels.
DecodedImage decodeImage(const void* data, std::size_t size, const std::string& nameForErrors, PixelBudget* budget = nullptr);

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
