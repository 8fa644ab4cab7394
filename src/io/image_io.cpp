#include "io/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <new>
#include <optional>
#include <stdexcept>
#include <string_view>

#include "io/atomic_file.h"
#include "io/image_decoders.h"
#include "io/input_file.h"
#include "io/reduced_image.h"
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
            if (!warned)
                warn(std::string("no captions on images: the font ") + kCaptionFont +
                     " was not found (Debian: apt-get install fonts-dejavu-core)");
            warned = true;
            return;
        }
    }
}

// An OpenImageIO reader on bytes in memory; the proxy must outlive it.
std::unique_ptr<OIIO::ImageInput> openImage(const unsigned char* bytes, std::size_t size,
                                            OIIO::Filesystem::IOMemReader& proxy, const std::string& name) {
    const char* format = formatOf(bytes, size);
    if (!format) throw fileError(name, "not an image format subdfit reads (PNG, JPEG, WebP, BMP, GIF, TIFF, EXR)");
    auto in = OIIO::ImageInput::open(std::string("memory.") + format, nullptr, &proxy);
    if (!in) throw fileError(name, "corrupt image: " + oneLine(OIIO::geterror()));
    return in;
}

bool streams(const char* format, const ImageHeader& header) {
    return (std::string_view(format) == "png" || std::string_view(format) == "jpg") && !header.interlaced;
}

ImageHeader checkedHeader(const ImageHeader& header, const char* format, const std::string& name) {
    const std::string size = std::to_string(header.width) + " x " + std::to_string(header.height);
    if (header.width <= 0 || header.height <= 0 || header.channels <= 0 || header.pixels() > kMaxImagePixels)
        throw fileError(
            name, "image of " + size + " pixels, more than subdfit reads (" + std::to_string(kMaxImagePixels) + ")");
    if (!streams(format, header) && header.pixels() > kMaxWholeImagePixels)
        throw fileError(
            name, "image of " + size + " pixels " +
                      (header.interlaced ? "stored interlaced" : "in a format decoded whole (all but PNG and JPEG)") +
                      ": more than the " + std::to_string(kMaxWholeImagePixels) + " subdfit decodes whole");
    if (header.channels > kMaxImageChannels)
        throw fileError(name, "image of " + std::to_string(header.channels) + " channels, more than the " +
                                  std::to_string(kMaxImageChannels) + " subdfit reads");
    return header;
}

ImageHeader checkedHeader(const OIIO::ImageSpec& spec, const char* format, const std::string& name) {
    if (spec.depth > 1) throw fileError(name, "a volume image (depth " + std::to_string(spec.depth) + ")");
    return checkedHeader(ImageHeader{spec.width, spec.height, spec.nchannels, false}, format, name);
}

// The header of a format read here, not by OpenImageIO; nothing for the others.
std::optional<ImageHeader> ownHeader(std::span<const unsigned char> bytes, std::string_view format,
                                     const std::string& name) {
    std::optional<ImageHeader> header;
    if (format == "png") header = pngHeader(bytes);
    else if (format == "jpg") header = jpegHeader(bytes);
    else if (format == "gif") header = gifHeader(bytes);
    else if (format == "webp") header = webpHeader(bytes);
    else return std::nullopt;
    if (!header)
        throw fileError(name,
                        std::string("corrupt image: no ") + (format == "jpg" ? "JPEG frame" : "valid") + " header");
    return header;
}

int dividedUp(int n, int d) { return (n + d - 1) / d; }

// The smallest whole factor that brings both sides to kMaxDecodedSide.
int sideFactor(const ImageHeader& header) {
    return std::max(dividedUp(header.width, kMaxDecodedSide), dividedUp(header.height, kMaxDecodedSide));
}

// Rows of an OpenImageIO reader, a strip at a time in the file's channels, made RGBA into `reduced`.
void readStrips(OIIO::ImageInput& in, const ImageHeader& header, ReducedImage& reduced, const std::string& name) {
    constexpr int kStripRows = 64;
    const int channels = header.channels;
    std::vector<std::uint8_t> strip(std::size_t(header.width) * std::size_t(channels) * kStripRows);
    std::vector<std::uint8_t> row(std::size_t(header.width) * 4);
    const int yBegin = in.spec().y;
    for (int y0 = 0; y0 < header.height; y0 += kStripRows) {
        const int rows = std::min(kStripRows, header.height - y0);
        if (!in.read_scanlines(0, 0, yBegin + y0, yBegin + y0 + rows, 0, 0, channels, OIIO::TypeDesc::UINT8,
                               strip.data()))
            throw fileError(name, "corrupt image: " + oneLine(in.geterror()));
        for (int r = 0; r < rows; ++r) {
            for (std::size_t x = 0; x < std::size_t(header.width); ++x) {
                const std::uint8_t* p =
                    strip.data() + (std::size_t(r) * std::size_t(header.width) + x) * std::size_t(channels);
                std::uint8_t* q = row.data() + x * 4;
                if (channels <= 2) {  // grey, grey + alpha
                    q[0] = q[1] = q[2] = p[0];
                    q[3] = channels == 2 ? p[1] : 255;
                } else {
                    q[0] = p[0], q[1] = p[1], q[2] = p[2];
                    q[3] = channels >= 4 ? p[3] : 255;
                }
            }
            reduced.addRow(row.data());
        }
    }
}

// `image`'s first `channels` channels at width × height, resized where that differs.
std::vector<std::uint8_t> pixelsAt(const DecodedImage& image, int width, int height, int channels) {
    SUBDFIT_CHECK(width >= 1 && height >= 1 && image.width >= 1 && image.height >= 1);
    OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8),
                          const_cast<std::uint8_t*>(image.rgba.data()));
    OIIO::ImageBuf resized =
        width == image.width && height == image.height
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
    const char* format = formatOf(bytes, size);
    if (!format) throw fileError(name, "not an image format subdfit reads (PNG, JPEG, WebP, BMP, GIF, TIFF, EXR)");
    if (const auto header = ownHeader({bytes, size}, format, name)) return checkedHeader(*header, format, name);
    OIIO::Filesystem::IOMemReader memory(bytes, size);
    const auto in = openImage(bytes, size, memory, name);
    return checkedHeader(in->spec(), format, name);
}

int PixelBudget::spend(const ImageHeader& image, const std::string& name) {
    int factor = sideFactor(image);
    auto pixels = [&](int f) {
        return std::int64_t(dividedUp(image.width, f)) * std::int64_t(dividedUp(image.height, f));
    };
    while (pixels(factor) > left_ &&
           std::max(dividedUp(image.width, factor), dividedUp(image.height, factor)) > kSmallestBudgetedSide)
        ++factor;
    if (pixels(factor) > left_)
        throw fileError(name, "image of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                                  " pixels: with the images before it, more than the " + std::to_string(total_) +
                                  " pixels subdfit decodes for one file, even at " +
                                  std::to_string(kSmallestBudgetedSide) + " pixels a side");
    left_ -= pixels(factor);
    return factor;
}

DecodePlan planDecode(const void* data, std::size_t size, const std::string& name, PixelBudget* budget) {
    const ImageHeader header = readImageHeader(data, size, name);
    return {.header = header, .factor = budget ? budget->spend(header, name) : sideFactor(header)};
}

DecodedImage decodeImage(const void* data, std::size_t size, const std::string& name, const DecodePlan& plan) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    const char* format = formatOf(bytes, size);
    try {
        if (format && std::string_view(format) == "png")
            return decodePng({bytes, size}, plan.header, plan.factor, name);
        if (format && std::string_view(format) == "jpg")
            return decodeJpeg({bytes, size}, plan.header, plan.factor, name);
        OIIO::Filesystem::IOMemReader memory(bytes, size);
        const auto in = openImage(bytes, size, memory, name);  // refuses an unknown format
        const ImageHeader header = checkedHeader(in->spec(), format, name);
        if (header.width != plan.header.width || header.height != plan.header.height)
            throw fileError(name, "corrupt image: its header says " + std::to_string(plan.header.width) + " x " +
                                      std::to_string(plan.header.height) + ", its reader " +
                                      std::to_string(header.width) + " x " + std::to_string(header.height));
        ReducedImage reduced(header.width, header.height, plan.factor);
        readStrips(*in, header, reduced, name);
        in->close();
        return {reduced.width(), reduced.height(), reduced.take()};
    } catch (const std::bad_alloc&) {
        throw fileError(name, "out of memory while decoding it");
    } catch (const std::length_error&) {
        throw fileError(name, "out of memory while decoding it");
    }
}

DecodedImage decodeImage(const void* data, std::size_t size, const std::string& name, PixelBudget* budget) {
    return decodeImage(data, size, name, planDecode(data, size, name, budget));
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
    if (!out || !out->supports("ioproxy"))
        throw Error(std::string("no in-memory ") + (jpeg ? "JPEG" : "PNG") + " writer");
    OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
    if (jpeg) {
        spec.attribute("Compression", "jpeg:" + std::to_string(std::clamp(quality, 1, 100)));
        if (fullChroma) spec.attribute("jpeg:subsampling", "4:4:4");
    }
    if (!out->set_ioproxy(&proxy) || !out->open(name, spec) ||
        !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close())
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
