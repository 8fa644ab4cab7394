#include "io/image_header.h"

#include <cstddef>

namespace subdfit::io {

std::optional<ImageSize> jpegSize(std::span<const unsigned char> bytes) {
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
            if (length < 7) return std::nullopt;
            const ImageSize size{u16(at + 7), u16(at + 5)};
            if (size.width == 0 || size.height == 0) return std::nullopt;
            return size;
        }
        at += 2 + length;
    }
    return std::nullopt;
}

}  // namespace subdfit::io
