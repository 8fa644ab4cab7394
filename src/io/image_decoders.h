#pragma once
// The decoders image_io.cpp hands PNG and JPEG to: libpng and libjpeg-turbo used directly, so that
// rows stream into a ReducedImage (a texture larger than subdfit uses is never held whole), a
// JPEG decodes at 1/2, 1/4 or 1/8 by its own DCT scaling, a progressive JPEG's scans are counted
// and capped, and every message a library has becomes part of one line naming the image.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "io/image_header.h"

namespace subdfit::io {

struct DecodedImage;

// `header` is what pngHeader / jpegHeader read from the same bytes; the result is `factor` times
// smaller on each side (rounded up). Throws subdfit::Error naming `name` for a corrupt or
// truncated image. A JPEG whose entropy-coded data is damaged decodes as well as it can with one
// warning (as browsers and engines draw it); a PNG's damage is refused.
DecodedImage decodePng(std::span<const unsigned char> bytes, const ImageHeader& header, int factor,
                       const std::string& name);
DecodedImage decodeJpeg(std::span<const unsigned char> bytes, const ImageHeader& header, int factor,
                        const std::string& name);

// A progressive JPEG's scans beyond this are refused: an ordinary one has about ten, and each
// scan costs a pass over the whole image.
inline constexpr int kMaxJpegScans = 100;

}  // namespace subdfit::io
