// libjpeg-turbo on bytes in memory, its errors back through longjmp (libjpeg's own way): nothing
// with a destructor lives between the setjmp and the libjpeg calls. Output rows are RGBA (the
// library's JCS_EXT_RGBA) or, for CMYK, converted here as OpenImageIO does.
#include <cstdio>  // jpeglib.h needs FILE

#include <jpeglib.h>

#include <csetjmp>
#include <cstring>

#include "io/image_decoders.h"
#include "io/image_io.h"
#include "io/reduced_image.h"
#include "util/error.h"
#include "util/printable.h"
#include "util/warnings.h"

namespace subdfit::io {
namespace {

struct JpegErrors {
    jpeg_error_mgr manager;  // first: libjpeg's err pointer is cast back to this
    std::jmp_buf jump;
    char error[JMSG_LENGTH_MAX];
    char firstWarning[JMSG_LENGTH_MAX];
    long warnings;
};

[[noreturn]] void onError(j_common_ptr jpeg) {
    auto* errors = reinterpret_cast<JpegErrors*>(jpeg->err);
    (*jpeg->err->format_message)(jpeg, errors->error);
    std::longjmp(errors->jump, 1);
}

// Level -1: a warning (corrupt entropy-coded data, a premature end); others are traces.
void onMessage(j_common_ptr jpeg, int level) {
    auto* errors = reinterpret_cast<JpegErrors*>(jpeg->err);
    if (level >= 0) return;
    if (errors->warnings++ == 0) (*jpeg->err->format_message)(jpeg, errors->firstWarning);
}

void onProgress(j_common_ptr jpeg) {
    auto* decompress = reinterpret_cast<j_decompress_ptr>(jpeg);
    if (decompress->input_scan_number > kMaxJpegScans) {
        auto* errors = reinterpret_cast<JpegErrors*>(jpeg->err);
        std::snprintf(errors->error, sizeof errors->error, "more than %d scans", kMaxJpegScans);
        std::longjmp(errors->jump, 1);
    }
}

// The largest of libjpeg's DCT scalings (1/1, 1/2, 1/4, 1/8) that divides `factor`.
int dctScale(int factor) {
    for (int scale : {8, 4, 2})
        if (factor % scale == 0) return scale;
    return 1;
}

int dividedUp(int n, int d) { return (n + d - 1) / d; }

bool readRows(jpeg_decompress_struct& jpeg, JpegErrors& errors, std::span<const unsigned char> bytes, int scale,
              std::uint8_t* row, ReducedImage& reduced, int width, int height) {
    if (setjmp(errors.jump)) return false;
    jpeg_mem_src(&jpeg, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&jpeg, TRUE);
    if (int(jpeg.image_width) != width || int(jpeg.image_height) != height) {
        std::snprintf(errors.error, sizeof errors.error, "its frame header is not the first one read");
        return false;
    }
    const bool cmyk = jpeg.jpeg_color_space == JCS_CMYK || jpeg.jpeg_color_space == JCS_YCCK;
    jpeg.out_color_space = cmyk ? JCS_CMYK : JCS_EXT_RGBA;
    jpeg.scale_num = 1;
    jpeg.scale_denom = unsigned(scale);
    jpeg_start_decompress(&jpeg);
    if (int(jpeg.output_width) != dividedUp(width, scale) || int(jpeg.output_height) != dividedUp(height, scale) ||
        jpeg.output_components != 4) {
        std::snprintf(errors.error, sizeof errors.error, "unexpected output layout");
        return false;
    }
    while (jpeg.output_scanline < jpeg.output_height) {
        JSAMPROW rows[1] = {row};
        if (jpeg_read_scanlines(&jpeg, rows, 1) != 1) {
            std::snprintf(errors.error, sizeof errors.error, "no row decoded");
            return false;
        }
        if (cmyk)  // Adobe's CMYK, stored inverted
            for (unsigned x = 0; x < jpeg.output_width; ++x) {
                std::uint8_t* p = row + std::size_t(x) * 4;
                const unsigned k = p[3];
                p[0] = std::uint8_t(p[0] * k / 255), p[1] = std::uint8_t(p[1] * k / 255),
                p[2] = std::uint8_t(p[2] * k / 255);
                p[3] = 255;
            }
        reduced.addRow(row);
    }
    return true;
}

}  // namespace

DecodedImage decodeJpeg(std::span<const unsigned char> bytes, const ImageHeader& header, int factor,
                        const std::string& name) {
    const int scale = dctScale(factor);
    const int scaledWidth = dividedUp(header.width, scale), scaledHeight = dividedUp(header.height, scale);
    ReducedImage reduced(scaledWidth, scaledHeight, factor / scale);
    std::vector<std::uint8_t> row(std::size_t(scaledWidth) * 4);

    JpegErrors errors{};
    jpeg_decompress_struct jpeg{};
    jpeg.err = jpeg_std_error(&errors.manager);
    errors.manager.error_exit = onError;
    errors.manager.emit_message = onMessage;
    jpeg_progress_mgr progress{};
    progress.progress_monitor = onProgress;
    jpeg_create_decompress(&jpeg);
    jpeg.progress = &progress;
    const bool decoded = readRows(jpeg, errors, bytes, scale, row.data(), reduced, header.width, header.height);
    jpeg_destroy_decompress(&jpeg);
    if (!decoded) throw fileError(name, "corrupt image: " + printable(errors.error, 160));
    if (errors.warnings > 0)
        warn(name + ": damaged JPEG data (" + printable(errors.firstWarning, 120) +
             "): decoded as well as it could be");
    return {reduced.width(), reduced.height(), reduced.take()};
}

}  // namespace subdfit::io
