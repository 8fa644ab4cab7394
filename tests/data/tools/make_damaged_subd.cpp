// Writes tests/data/damaged-subd/ (see the README there) from box.subd in it: the same file with
// one bit flipped inside a section's zstd frame, and with its base colour JPEG's Huffman table
// made unsound, each with the file's checksum (and the section's, where re-compressed) made right
// again, as someone who meant it would. Build and run from the repository root, after building subdfit:
//   g++ -std=c++20 -Isrc -Itests/support tests/data/tools/make_damaged_subd.cpp build/src/libsubdfit_util.a -lzstd -lxxhash \
//       -o /tmp/make_damaged_subd && /tmp/make_damaged_subd tests/data/damaged-subd
#include <zstd.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "subd_bytes.h"
#include "util/hash.h"

using Bytes = std::vector<unsigned char>;

Bytes read(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write(const std::string& path, Bytes bytes) {
    const std::uint64_t sum = subdfit::hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size() - 8});
    std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

std::uint32_t u32(const Bytes& b, std::size_t at) {
    std::uint32_t v;
    std::memcpy(&v, b.data() + at, 4);
    return v;
}

// Where a section's stored frame starts in the file, and its size.
std::pair<std::size_t, std::size_t> section(const Bytes& file, const char* tag) {
    std::size_t at = 16;  // version 7: magic, version, flags, count, decode triangles
    for (std::uint32_t k = 0; k < u32(file, 8); ++k) {
        const std::size_t stored = u32(file, at + 4);
        if (std::memcmp(file.data() + at, tag, 4) == 0) return {at + 12, stored};
        at += 12 + stored;
    }
    throw std::runtime_error(std::string("no ") + tag + " section");
}

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : ".";
    const Bytes box = read(dir + "/box.subd");

    Bytes flipped = box;
    const auto [disp, dispSize] = section(box, "DISP");
    flipped[disp + dispSize / 2] ^= 0x10;
    write(dir + "/section_bit_flipped.subd", flipped);

    // BCOL: varint T, varint nodes, u8 coding, varint n, the JPEG. Its first DHT's 1-bit codes: 3
    // (two at most exist, and all ones is reserved: libjpeg stops at "Bogus Huffman table").
    const auto [bcol, bcolSize] = section(box, "BCOL");
    Bytes raw(u32(box, bcol - 4));
    ZSTD_decompress(raw.data(), raw.size(), box.data() + bcol, bcolSize);
    for (std::size_t k = 0; k + 5 < raw.size(); ++k)
        if (raw[k] == 0xFF && raw[k + 1] == 0xC4) {
            raw[k + 5] = 3;
            break;
        }
    const Bytes frame = subdfit::test::checksummedFrame(raw);
    Bytes damaged(box.begin(), box.begin() + std::ptrdiff_t(bcol - 12));
    damaged.insert(damaged.end(), box.begin() + std::ptrdiff_t(bcol - 12), box.begin() + std::ptrdiff_t(bcol - 4));
    const std::uint32_t storedSize = std::uint32_t(frame.size());
    std::memcpy(damaged.data() + bcol - 8, &storedSize, 4);
    damaged.insert(damaged.end(), box.begin() + std::ptrdiff_t(bcol - 4), box.begin() + std::ptrdiff_t(bcol));
    damaged.insert(damaged.end(), frame.begin(), frame.end());
    damaged.insert(damaged.end(), box.begin() + std::ptrdiff_t(bcol + bcolSize), box.end());
    write(dir + "/jpeg_huffman_table_damaged.subd", damaged);
    return 0;
}
