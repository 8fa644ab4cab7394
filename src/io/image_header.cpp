#include "io/image_header.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>

namespace subdfit::io {

std::optional<ImageHeader> jpegHeader(std::span<const unsigned char> bytes) {
    // JPEG (ITU T.81 B.1): SOI, then segments FF xx with a 16-bit big-endian length that
    // counts itself; SOF0..SOF15 but DHT (C4), JPG (C8) and DAC (CC) carry the frame size.
    auto u16 = [&](std::size_t at) { return int(bytes[at]) << 8 | int(bytes[at + 1]); };
    if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return std::nullopt;
    std::size_t at = 2;
    while (at + 4 <= bytes.size()) {
        if (bytes[at] != 0xFF) return std::nullopt;
        const unsigned char marker = bytes[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0xD9 || marker == 0xDA) return std::nullopt;  // end of image or scan before a frame
        const std::size_t length = std::size_t(u16(at + 2));
        if (length < 2 || at + 2 + length > bytes.size()) return std::nullopt;
        const bool frame = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
        if (frame) {
            // length, precision, height, width, components
            if (length < 8) return std::nullopt;
            // SOF2, SOF6, SOF10, SOF14: progressive.
            const bool progressive = (marker & 0x03) == 0x02;
            const ImageHeader header{u16(at + 7), u16(at + 5), int(bytes[at + 9]), progressive};
            if (header.width == 0 || header.height == 0 || header.channels == 0) return std::nullopt;
            return header;
        }
        at += 2 + length;
    }
    return std::nullopt;
}

std::optional<ImageHeader> pngHeader(std::span<const unsigned char> bytes) {
    // PNG 1.2: the 8-byte signature, then IHDR first: length 13, width, height (big-endian),
    // bit depth, colour type, compression, filter, interlace.
    static constexpr unsigned char kSignature[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
    if (bytes.size() < 33 || !std::equal(std::begin(kSignature), std::end(kSignature), bytes.begin()))
        return std::nullopt;
    if (!std::equal(bytes.begin() + 12, bytes.begin() + 16, "IHDR")) return std::nullopt;
    auto u32 = [&](std::size_t at) {
        return std::uint32_t(bytes[at]) << 24 | std::uint32_t(bytes[at + 1]) << 16 | std::uint32_t(bytes[at + 2]) << 8 |
               bytes[at + 3];
    };
    const std::uint32_t width = u32(16), height = u32(20);
    if (width == 0 || height == 0 || width > 0x7FFFFFFFu || height > 0x7FFFFFFFu) return std::nullopt;
    int channels = 0;
    switch (bytes[25]) {
        case 0: channels = 1; break;  // grey
        case 2: channels = 3; break;  // RGB
        case 3: channels = 3; break;  // palette
        case 4: channels = 2; break;  // grey + alpha
        case 6: channels = 4; break;  // RGBA
        default: return std::nullopt;
    }
    return ImageHeader{int(width), int(height), channels, bytes[28] != 0};
}

std::optional<ImageHeader> gifHeader(std::span<const unsigned char> bytes) {
    // GIF89a: "GIF87a" or "GIF89a", then the logical screen's width and height (little-endian).
    if (bytes.size() < 10 || !std::equal(bytes.begin(), bytes.begin() + 4, "GIF8")) return std::nullopt;
    const int width = int(bytes[6]) | int(bytes[7]) << 8, height = int(bytes[8]) | int(bytes[9]) << 8;
    if (width == 0 || height == 0) return std::nullopt;
    return ImageHeader{width, height, 4, false};
}

std::optional<ImageHeader> webpHeader(std::span<const unsigned char> bytes) {
    // RIFF container: "RIFF" size "WEBP", then the first chunk: "VP8X" (canvas size minus one, 24
    // bits each, at 24), "VP8 " (a key frame: 14-bit sizes at 26) or "VP8L" (14-bit sizes minus
    // one, packed, at 21).
    if (bytes.size() < 30 || !std::equal(bytes.begin(), bytes.begin() + 4, "RIFF") ||
        !std::equal(bytes.begin() + 8, bytes.begin() + 12, "WEBP"))
        return std::nullopt;
    auto u24 = [&](std::size_t at) { return int(bytes[at]) | int(bytes[at + 1]) << 8 | int(bytes[at + 2]) << 16; };
    auto u16 = [&](std::size_t at) { return int(bytes[at]) | int(bytes[at + 1]) << 8; };
    int width = 0, height = 0;
    if (std::equal(bytes.begin() + 12, bytes.begin() + 16, "VP8X")) {
        width = u24(24) + 1, height = u24(27) + 1;
    } else if (std::equal(bytes.begin() + 12, bytes.begin() + 16, "VP8 ")) {
        width = u16(26) & 0x3FFF, height = u16(28) & 0x3FFF;
    } else if (std::equal(bytes.begin() + 12, bytes.begin() + 16, "VP8L")) {
        const std::uint32_t bits = std::uint32_t(bytes[21]) | std::uint32_t(bytes[22]) << 8 |
                                   std::uint32_t(bytes[23]) << 16 | std::uint32_t(bytes[24]) << 24;
        width = int(bits & 0x3FFF) + 1, height = int((bits >> 14) & 0x3FFF) + 1;
    } else {
        return std::nullopt;
    }
    if (width == 0 || height == 0) return std::nullopt;
    return ImageHeader{width, height, 4, true};
}

std::string jpegStructureProblem(std::span<const unsigned char> bytes) {
    // ITU T.81 B.2-B.3; the checks are those libjpeg stops at (jdmarker.c, jdhuff.c, jdphuff.c).
    auto u16 = [&](std::size_t at) { return std::size_t(bytes[at]) << 8 | bytes[at + 1]; };
    if (bytes.size() < 4 || bytes[0] != 0xFF || bytes[1] != 0xD8) return "no start of image";
    bool quant[4] = {}, huffman[2][4] = {};
    int components = 0;
    int componentIds[4] = {};
    bool frame = false, progressive = false, scan = false;
    std::size_t at = 2;
    for (;;) {
        if (at + 2 > bytes.size()) return "no end of image";
        if (bytes[at] != 0xFF) return "bytes between segments";
        const unsigned char marker = bytes[at + 1];
        if (marker == 0xFF) {  // fill byte
            ++at;
            continue;
        }
        if (marker == 0xD9) return scan ? "" : "no scan";
        if ((marker >= 0xD0 && marker <= 0xD7) || marker == 0x01 || marker == 0xD8) return "a stray marker";
        const bool known = marker == 0xC0 || marker == 0xC1 || marker == 0xC2 || marker == 0xC4 || marker == 0xDA ||
                           marker == 0xDB || marker == 0xDD || (marker >= 0xE0 && marker <= 0xEF) || marker == 0xFE;
        if (!known) return "an unsupported marker";
        if (at + 4 > bytes.size()) return "a segment cut short";
        const std::size_t length = u16(at + 2), begin = at + 4, end = at + 2 + length;
        if (length < 2 || end > bytes.size()) return "a segment longer than the file";
        if (marker == 0xDB) {  // quantisation tables
            for (std::size_t p = begin; p < end;) {
                const int precision = bytes[p] >> 4, id = bytes[p] & 15;
                const std::size_t size = 1 + (precision ? 128 : 64);
                if (precision > 1 || id > 3 || p + size > end) return "a bad quantisation table";
                quant[id] = true;
                p += size;
            }
        } else if (marker == 0xC4) {  // Huffman tables
            for (std::size_t p = begin; p < end;) {
                if (p + 17 > end) return "a bad Huffman table";
                const int kind = bytes[p] >> 4, id = bytes[p] & 15;
                if (kind > 1 || id > 3) return "a bad Huffman table";
                std::size_t symbols = 0, codes = 0;
                for (int bits = 1; bits <= 16; ++bits) {
                    codes += bytes[p + std::size_t(bits)];
                    symbols += bytes[p + std::size_t(bits)];
                    if (codes >= (std::size_t(1) << bits)) return "a bad Huffman table";  // all ones is reserved
                    codes <<= 1;
                }
                if (symbols > 256 || p + 17 + symbols > end) return "a bad Huffman table";
                if (kind == 0)
                    for (std::size_t k = 0; k < symbols; ++k)
                        if (bytes[p + 17 + k] > 15) return "a bad Huffman table";
                huffman[kind][id] = true;
                p += 17 + symbols;
            }
        } else if (marker == 0xC0 || marker == 0xC1 || marker == 0xC2) {  // the frame
            if (frame) return "two frames";
            frame = true;
            progressive = marker == 0xC2;
            if (length < 8) return "a bad frame header";
            components = bytes[begin + 5];
            if (bytes[begin] != 8 || u16(begin + 1) == 0 || u16(begin + 3) == 0 || components < 1 || components > 4 ||
                length != 8 + 3 * std::size_t(components))
                return "a bad frame header";
            for (int c = 0; c < components; ++c) {
                const std::size_t p = begin + 6 + 3 * std::size_t(c);
                const int h = bytes[p + 1] >> 4, v = bytes[p + 1] & 15;
                if (h < 1 || h > 4 || v < 1 || v > 4 || bytes[p + 2] > 3 || !quant[bytes[p + 2]])
                    return "a bad frame header";
                componentIds[c] = bytes[p];
            }
        } else if (marker == 0xDD) {
            if (length != 4) return "a bad restart interval";
        } else if (marker == 0xDA) {  // a scan, then its entropy-coded data up to the next marker
            if (!frame) return "a scan before the frame";
            const std::size_t count = length >= 3 ? bytes[begin] : 0;
            if (count < 1 || count > 4 || length != 6 + 2 * count) return "a bad scan header";
            const std::size_t tail = begin + 1 + 2 * count;
            const int ss = bytes[tail], se = bytes[tail + 1], ah = bytes[tail + 2] >> 4, al = bytes[tail + 2] & 15;
            const bool dc = ss == 0;
            if (progressive &&
                ((dc ? se != 0 : (ss > se || se > 63 || count != 1)) || (ah != 0 && al != ah - 1) || al > 13))
                return "a bad progression";
            for (std::size_t c = 0; c < count; ++c) {
                const int id = bytes[begin + 1 + 2 * c], dcTable = bytes[begin + 2 + 2 * c] >> 4,
                          acTable = bytes[begin + 2 + 2 * c] & 15;
                if (std::find(componentIds, componentIds + components, id) == componentIds + components)
                    return "a scan of a component the frame lacks";
                const bool needsDc = !progressive || (dc && ah == 0), needsAc = !progressive || !dc;
                if ((needsDc && (dcTable > 3 || !huffman[0][dcTable])) ||
                    (needsAc && (acTable > 3 || !huffman[1][acTable])))
                    return "a scan naming a Huffman table that is not defined";
            }
            scan = true;
            at = end;
            while (at + 1 < bytes.size() &&
                   !(bytes[at] == 0xFF && bytes[at + 1] != 0x00 && (bytes[at + 1] < 0xD0 || bytes[at + 1] > 0xD7)))
                ++at;
            continue;
        }
        at = end;
    }
}

}  // namespace subdfit::io
