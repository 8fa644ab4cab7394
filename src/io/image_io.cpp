#include "io/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <string_view>

#include "io/atomic_file.h"
#include "io/input_file.h"
#include "util/error.h"
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

}  // namespace

DecodedImage decodeImage(const void* data, std::size_t size, const std::string& name) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    const char* format = formatOf(bytes, size);
    if (!format) throw fileError(name, "not an image format subdfit reads (PNG, JPEG, WebP, BMP, GIF, TIFF, EXR)");
    OIIO::Filesystem::IOMemReader memory(bytes, size);
    auto in = OIIO::ImageInput::open(std::string("memory.") + format, nullptr, &memory);
    if (!in) throw fileError(name, "corrupt image: " + OIIO::geterror());
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1 ||
        std::int64_t(spec.width) * spec.height > kMaxImagePixels)
        throw fileError(name, "image of " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                                  " pixels, more than subdfit reads (" + std::to_string(kMaxImagePixels) + ")");
    const int channels = spec.nchannels;
    std::vector<std::uint8_t> pixels(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(channels));
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()))
        throw fileError(name, "corrupt image: " + in->geterror());
    in->close();
    DecodedImage image{spec.width, spec.height, std::vector<std::uint8_t>(std::size_t(spec.width) * spec.height * 4)};
    for (std::size_t i = 0, n = std::size_t(spec.width) * spec.height; i < n; ++i) {
        const std::uint8_t* p = pixels.data() + i * std::size_t(channels);
        std::uint8_t* q = image.rgba.data() + i * 4;
        if (channels <= 2) {  // grey, grey + alpha
            q[0] = q[1] = q[2] = p[0];
            q[3] = channels == 2 ? p[1] : 255;
        } else {
            q[0] = p[0], q[1] = p[1], q[2] = p[2];
            q[3] = channels >= 4 ? p[3] : 255;
        }
    }
    return image;
}

std::vector<std::uint8_t> encodeImage(const DecodedImage& image, int width, int height, ImageFormat format, int quality,
                                      bool fullChroma) {
    SUBDFIT_CHECK(width >= 1 && height >= 1 && image.width >= 1 && image.height >= 1);
    const bool jpeg = format == ImageFormat::Jpeg;
    const int channels = jpeg ? 3 : 4;  // JPEG has no alpha
    OIIO::ImageBuf source(OIIO::ImageSpec(image.width, image.height, 4, OIIO::TypeDesc::UINT8),
                          const_cast<std::uint8_t*>(image.rgba.data()));
    OIIO::ImageBuf resized = width == image.width && height == image.height
                                 ? source
                                 : OIIO::ImageBufAlgo::resize(source, "", 0.0f, OIIO::ROI(0, width, 0, height, 0, 1, 0, 4));
    std::vector<std::uint8_t> pixels(size_t(width) * size_t(height) * size_t(channels));
    if (!resized.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, channels), OIIO::TypeDesc::UINT8, pixels.data()))
        throw Error("cannot resize an image: " + resized.geterror());
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
        throw Error(std::string("cannot encode an image: ") + out->geterror());
    return bytes;
}

DecodedImage readImage(const std::filesystem::path& path) {
    const std::string bytes = readInputFile(path);
    return decodeImage(bytes.data(), bytes.size(), path.string());
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
            throw fileError(path.string(), "could not write image: " + out->geterror());
    });
}

}  // namespace subdfit::io
