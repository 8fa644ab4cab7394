#include "io/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <optional>
#include <string_view>

#include "io/atomic_file.h"
#include "io/input_file.h"
#include "util/error.h"
#include "util/printable.h"
#include "util/warnings.h"

namespace subdfit::io {
namespace {

// OpenImageIO picks a reader by file extension; bytes in memory have none, so the signature
// names the format.
const char* formatOf(const unsigned char* p, std::size_t n) {
    auto starts = [&](std::string_view magic, std::size_t at = 0) {
        return n >= at + magic.size() && std::memcmp(p + at, magic.data(), magic.size()) == 0;
    };
    if (starts("\x89PNG\r\n\x1a\n")) return "png";
    if (starts("\xff\xd8\xff")) return "jpg";
    if (starts("RIFF") && starts("WEBP", 8)) return "webp";
    if (starts("BM")) return "bmp";
    if (starts("GIF8")) return "gif";
    if (starts("II*") || starts("MM\0*")) return "tif";
    if (starts("\x76\x2f\x31\x01")) return "exr";
    return nullptr;
}

// The font every caption is drawn in, as OpenImageIO finds it among the system's fonts.
constexpr const char* kCaptionFont = "DejaVuSans";

// Draws `texts` into `rgb` (8-bit RGB, rows top-down, as `spec` says), clipped to the image.
// Without the font, warns once and draws nothing.
void drawTexts(const OIIO::ImageSpec& spec, std::vector<unsigned char>& rgb, const std::vector<ImageText>& texts) {
    OIIO::ImageBuf image(spec, rgb.data());
    for (const ImageText& t : texts) {
        // OpenImageIO 2.4 aborts on a text whose rows all lie outside the image.
        if (t.y >= spec.height || t.y + t.size <= 0 || t.x >= spec.width) continue;
        const float colour[3] = {t.colour.r, t.colour.g, t.colour.b};
        if (!OIIO::ImageBufAlgo::render_text(image, t.x, t.y, t.text, t.size, kCaptionFont, colour,
                                             OIIO::ImageBufAlgo::TextAlignX::Left,
                                             OIIO::ImageBufAlgo::TextAlignY::Top)) {
            static bool warned = false;
            if (!warned) warn(std::string("no captions on images: the font ") + kCaptionFont +
                              " was not found (Debian: apt-get install fonts-dejavu-core)");
            warned = true;
            return;
        }
    }
}

// An OpenImageIO reader on bytes in memory; the proxy must outlive it.
std::unique_ptr<OIIO::ImageInput> openImage(const unsigned char* bytes, std::size_t size, OIIO::Filesystem::IOMemReader& proxy,
                                            const std::string& name) {
    const char* format = formatOf(bytes, size);
    if (!format) throw fileError(name, "not an image format subdfit reads (PNG, JPEG, WebP, BMP, GIF, TIFF, EXR)");
    auto in = OIIO::ImageInput::open(std::string("memory.") + format, nullptr, &proxy);
    if (!in) throw fileError(name, "corrupt image: " + oneLine(OIIO::geterror()));
    return in;
}

ImageHeader checkedHeader(const ImageHeader& header, const std::string& name) {
    if (header.width <= 0 || header.height <= 0 || header.channels <= 0 || header.pixels() > kMaxImagePixels)
        throw fileError(name, "image of " + std::to_string(header.width) + " x " + std::to_string(header.height) +
                                  " pixels, more than subdfit reads (" + std::to_string(kMaxImagePixels) + ")");
    return header;
}

ImageHeader checkedHeader(const OIIO::ImageSpec& spec, const std::string& name) {
    if (spec.depth > 1) throw fileError(name, "a volume image (depth " + std::to_string(spec.depth) + ")");
    return checkedHeader(ImageHeader{spec.width, spec.height, spec.nchannels}, name);
}

// `image`'s first `channels` channels at width × height, resized where that differs.
std::vector<std::uint8_t> pixelsAt(const DecodedImage& image, int width, int height, int channels) {
    SUBDFIT_CHECK(width >= 1 && height >= 1 && image.width >= 1 && image.height >= 1);
    OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8),
                          const_cast<std::uint8_t*>(image.rgba.data()));
    OIIO::ImageBuf resized = width == image.width && height == image.height
                                 ? source
                                 : OIIO::ImageBufAlgo::resize(source, "", 0.0f, OIIO::ROI(0, width, 0, height, 0, 1, 0, 4));
    std::vector<std::uint8_t> pixels(size_t(width) * size_t(height) * size_t(channels));
    if (!resized.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, channels), OIIO::TypeDesc::UINT8, pixels.data()))
        throw Error("cannot resize an image: " + oneLine(resized.geterror()));
    return pixels;
}

}  // namespace

ImageHeader readImageHeader(const void* data, std::size_t size, const std::string& name) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    if (const char* format = formatOf(bytes, size); format && std::string_view(format) == "jpg") {
        const std::optional<ImageHeader> header = jpegHeader({bytes, size});
        if (!header) throw fileError(name, "corrupt image: no JPEG frame header");
        return checkedHeader(*header, name);
    }
    OIIO::Filesystem::IOMemReader memory(bytes, size);
    const auto in = openImage(bytes, size, memory, name);
    return checkedHeader(in->spec(), name);
}

void PixelBudget::spend(const ImageHeader& image, const std::string& name) {
    if (image.pixels() > left_)
        throw fileError(name, "image of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                                  " pixels: with the images before it, more than the " + std::to_string(total_) +
                                  " pixels subdfit decodes for one file");
    left_ -= image.pixels();
}

DecodedImage decodeImage(const void* data, std::size_t size, const std::string& name, PixelBudget* budget) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    OIIO::Filesystem::IOMemReader memory(bytes, size);
    const auto in = openImage(bytes, size, memory, name);
    const ImageHeader header = checkedHeader(in->spec(), name);
    if (budget) budget->spend(header, name);
    const int channels = header.channels;
    DecodedImage image{header.width, header.height, std::vector<std::uint8_t>(std::size_t(header.pixels()) * 4)};
    // A strip of rows at a time in the file's channels, expanded into the RGBA buffer.
    constexpr int kStripRows = 64;
    std::vector<std::uint8_t> strip(std::size_t(header.width) * std::size_t(channels) * kStripRows);
    const int yBegin = in->spec().y;
    for (int y0 = 0; y0 < header.height; y0 += kStripRows) {
        const int rows = std::min(kStripRows, header.height - y0);
        if (!in->read_scanlines(0, 0, yBegin + y0, yBegin + y0 + rows, 0, 0, channels, OIIO::TypeDesc::UINT8, strip.data()))
            throw fileError(name, "corrupt image: " + oneLine(in->geterror()));
        for (std::size_t i = 0, n = std::size_t(header.width) * std::size_t(rows); i < n; ++i) {
            const std::uint8_t* p = strip.data() + i * std::size_t(channels);
            std::uint8_t* q = image.rgba.data() + (std::size_t(y0) * std::size_t(header.width) + i) * 4;
            if (channels <= 2) {  // grey, grey + alpha
                q[0] = q[1] = q[2] = p[0];
                q[3] = channels == 2 ? p[1] : 255;
            } else {
                q[0] = p[0], q[1] = p[1], q[2] = p[2];
                q[3] = channels >= 4 ? p[3] : 255;
            }
        }
    }
    in->close();
    return image;
}

DecodedImage resizedImage(const DecodedImage& image, int width, int height) {
    return {width, height, pixelsAt(image, width, height, 4)};
}

std::vector<std::uint8_t> encodeImage(const DecodedImage& image, int width, int height, ImageFormat format, int quality,
                                      bool fullChroma) {
    const bool jpeg = format == ImageFormat::Jpeg;
    const int channels = jpeg ? 3 : 4;  // JPEG has no alpha
    const std::vector<std::uint8_t> pixels = pixelsAt(image, width, height, channels);
    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    const char* name = jpeg ? "image.jpg" : "image.png";
    auto out = OIIO::ImageOutput::create(name);
    if (!out || !out->supports("ioproxy")) throw Error(std::string("no in-memory ") + (jpeg ? "JPEG" : "PNG") + " writer");
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    if (jpeg) {
        spec.attribute("Compression", "jpeg:" + std::to_string(std::clamp(quality, 1, 100)));
        if (fullChroma) spec.attribute("jpeg:subsampling", "4:4:4");
    }
    if (!out->set_ioproxy(&proxy) || !out->open(name, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
        !out->close())
        throw Error(std::string("cannot encode an image: ") + oneLine(out->geterror()));
    return bytes;
}

DecodedImage readImage(const std::filesystem::path& path, PixelBudget* budget) {
    const std::string bytes = readInputFile(path);
    return decodeImage(bytes.data(), bytes.size(), path.string(), budget);
}

void writeImage(const std::filesystem::path& path, const std::vector<glm::vec4>& pixels, int width, int height) {
    writeImage(path, pixels, width, height, {});
}

void writeImage(const std::filesystem::path& path, const std::vector<glm::vec4>& pixels, int width, int height,
                const std::vector<ImageText>& texts) {
    std::vector<unsigned char> rgb(size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const auto& p = pixels[size_t(height - 1 - y) * width + x];  // GL rows are bottom-up
            for (int c = 0; c < 3; ++c)
                rgb[(size_t(y) * width + x) * 3 + c] = (unsigned char)(std::clamp(p[c], 0.0f, 1.0f) * 255.0f + 0.5f);
        }
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    if (!texts.empty()) drawTexts(spec, rgb, texts);
    writeAtomically(path, [&](const std::filesystem::path& temporary) {
        auto out = OIIO::ImageOutput::create(temporary.string());
        if (!out) throw fileError(path.string(), "no image writer for this extension");
        if (!out->open(temporary.string(), spec) || !out->write_image(OIIO::TypeDesc::UINT8, rgb.data()) ||
            !out->close())
            throw fileError(path.string(), "could not write image: " + oneLine(out->geterror()));
    });
}

}  // namespace subdfit::io
