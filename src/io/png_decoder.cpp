// libpng's sequential reader on bytes in memory. Its errors come back through longjmp (libpng's
// own way): nothing with a destructor lives between the setjmp and the libpng calls, and what a
// decode builds (the row buffer, the ReducedImage) is made before and owned by the caller.
#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "io/image_decoders.h"
#include "io/image_io.h"
#include "io/reduced_image.h"
#include "util/error.h"
#include "util/printable.h"

namespace subdfit::io {
namespace {

struct PngSource {
    const unsigned char* data;
    std::size_t size, at;
    char error[256];  // libpng's message, for the one line this decode fails with
};

void readBytes(png_structp png, png_bytep out, png_size_t n) {
    auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
    if (n > source->size - source->at) png_error(png, "the file ends early");
    std::memcpy(out, source->data + source->at, n);
    source->at += n;
}

[[noreturn]] void onError(png_structp png, png_const_charp message) {
    auto* source = static_cast<PngSource*>(png_get_error_ptr(png));
    std::snprintf(source->error, sizeof source->error, "%s", message);
    png_longjmp(png, 1);
}

// Benign (an ancillary chunk's CRC, an unknown profile): libpng would print them on stderr.
void onWarning(png_structp, png_const_charp) {}

// Reads every row into `rows` (whole: `image` holds them all when interlaced, else one at a time
// into `row` and on into `reduced`). False, with source.error set, when libpng fails.
bool readRows(png_structp png, png_infop info, PngSource& source, std::uint8_t* row, std::uint8_t* image,
              ReducedImage& reduced, int width, int height) {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_read_fn(png, &source, readBytes);
    png_read_info(png, info);
    if (int(png_get_image_width(png, info)) != width || int(png_get_image_height(png, info)) != height)
        png_error(png, "its header changed between readings");
    png_set_expand(png);    // palette to RGB, grey below 8 bits to 8, tRNS to alpha
    png_set_scale_16(png);  // 16 bits to 8, rounded
    png_set_gray_to_rgb(png);
    png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
    const int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    if (png_get_rowbytes(png, info) != png_size_t(width) * 4) png_error(png, "unexpected row layout");
    if (passes > 1) {
        for (int pass = 0; pass < passes; ++pass)
            for (int y = 0; y < height; ++y)
                png_read_row(png, image + std::size_t(y) * std::size_t(width) * 4, nullptr);
        for (int y = 0; y < height; ++y) reduced.addRow(image + std::size_t(y) * std::size_t(width) * 4);
    } else {
        for (int y = 0; y < height; ++y) {
            png_read_row(png, row, nullptr);
            reduced.addRow(row);
        }
    }
    return true;
}

}  // namespace

DecodedImage decodePng(std::span<const unsigned char> bytes, const ImageHeader& header, int factor,
                       const std::string& name) {
    PngSource source{bytes.data(), bytes.size(), 0, {}};
    png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, onError, onWarning);
    if (!png) throw fileError(name, "out of memory while decoding it");
    png_infop info = png_create_info_struct(png);
    struct Release {
        png_structp* png;
        png_infop* info;
        ~Release() { png_destroy_read_struct(png, info, nullptr); }
    } release{&png, &info};
    if (!info) throw fileError(name, "out of memory while decoding it");
    png_set_user_limits(png, png_uint_32(header.width), png_uint_32(header.height));

    ReducedImage reduced(header.width, header.height, factor);
    std::vector<std::uint8_t> row(std::size_t(header.width) * 4);
    std::vector<std::uint8_t> whole(header.interlaced ? std::size_t(header.pixels()) * 4 : 0);
    if (!readRows(png, info, source, row.data(), whole.data(), reduced, header.width, header.height))
        throw fileError(name, "corrupt image: " + printable(source.error, 160));
    return {reduced.width(), reduced.height(), reduced.take()};
}

}  // namespace subdfit::io
