// The JPEG marker check every decoder of asset.subd runs before an image reaches a JPEG decoder
// (io::jpegStructureProblem): what libjpeg writes passes; what libjpeg stops at is named.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "io/image_header.h"
#include "io/image_io.h"

namespace subdfit::io {
namespace {

std::vector<unsigned char> jpeg(int width, int height, int quality, bool fullChroma) {
    DecodedImage image{width, height, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4)};
    for (std::size_t k = 0; k < image.rgba.size(); ++k) image.rgba[k] = std::uint8_t((k * 131) % 251);
    return encodeImage(image, width, height, ImageFormat::Jpeg, quality, fullChroma);
}

// The offset of the first marker `code` (FF code) outside entropy-coded data.
std::size_t markerAt(const std::vector<unsigned char>& bytes, unsigned char code) {
    for (std::size_t at = 2; at + 4 <= bytes.size();) {
        if (bytes[at + 1] == code) return at;
        at += 2 + (std::size_t(bytes[at + 2]) << 8 | bytes[at + 3]);
    }
    return 0;
}

TEST(JpegStructure, WhatLibjpegWritesPasses) {
    for (const auto& [w, h, q, full] : {std::tuple{1, 1, 90, false}, {64, 48, 50, true}, {257, 31, 100, false}})
        EXPECT_EQ(jpegStructureProblem(jpeg(w, h, q, full)), "") << w << " x " << h;
}

TEST(JpegStructure, WhatLibjpegStopsAtIsNamed) {
    const auto good = jpeg(40, 40, 90, false);
    auto cut = good;
    cut.resize(good.size() - 2);  // no EOI
    EXPECT_EQ(jpegStructureProblem(cut), "no end of image");
    auto huffman = good;
    huffman[markerAt(good, 0xC4) + 5] = 3;  // three 1-bit codes
    EXPECT_EQ(jpegStructureProblem(huffman), "a bad Huffman table");
    auto precision = good;
    precision[markerAt(good, 0xC0) + 4] = 12;
    EXPECT_EQ(jpegStructureProblem(precision), "a bad frame header");
    auto lossless = good;
    lossless[markerAt(good, 0xC0) + 1] = 0xC3;
    EXPECT_EQ(jpegStructureProblem(lossless), "an unsupported marker");
    auto table = good;
    const std::size_t sos = markerAt(good, 0xDA);
    table[sos + 6] = 0x33;  // the first component's DC and AC tables: 3, never defined
    EXPECT_EQ(jpegStructureProblem(table), "a scan naming a Huffman table that is not defined");
    auto length = good;
    length[markerAt(good, 0xDB) + 2] = 0xFF;
    EXPECT_EQ(jpegStructureProblem(length), "a segment longer than the file");
    EXPECT_EQ(jpegStructureProblem(std::vector<unsigned char>{0xFF, 0xD8, 0xFF, 0xD9}), "no scan");
}

}  // namespace
}  // namespace subdfit::io
