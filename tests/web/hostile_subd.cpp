// Writes .subd files that are whole and checksummed but ask the decoder for too much, for the web
// decoder's tests (tests/web/decode_test.mjs): each must be refused in one line, quickly and
// without growing the decoder's memory.
//   subdfit_hostile_subd OUT_DIR
#include <zstd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "export/byte_stream.h"
#include "util/hash.h"

namespace {

using subdfit::exporter::ByteWriter;
using Bytes = std::vector<unsigned char>;

struct Section {
    const char* tag;
    Bytes raw;
    std::uint32_t statedRawSize = 0;  // 0: the true size
};

Bytes container(const std::vector<Section>& sections) {
    ByteWriter file;
    file.putBytes({reinterpret_cast<const unsigned char*>("SUBD"), 4});
    file.put<std::uint16_t>(5);
    file.put<std::uint16_t>(0);
    file.put<std::uint32_t>(std::uint32_t(sections.size()));
    for (const auto& section : sections) {
        Bytes stored(ZSTD_compressBound(section.raw.size()));
        stored.resize(ZSTD_compress(stored.data(), stored.size(), section.raw.data(), section.raw.size(), 19));
        file.putBytes({reinterpret_cast<const unsigned char*>(section.tag), 4});
        file.put<std::uint32_t>(std::uint32_t(stored.size()));
        file.put<std::uint32_t>(section.statedRawSize ? section.statedRawSize : std::uint32_t(section.raw.size()));
        file.putBytes(stored);
    }
    const auto& bytes = file.bytes();
    file.put<std::uint64_t>(subdfit::hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    return std::move(file.bytes());
}

// A plain-coded CAGE (export/cage_coding.h) of `faces` copies of one quad over four vertices:
// tiny once compressed, but 2·64·faces triangles at decode's default 8 segments.
Bytes quadsCage(std::uint64_t faces) {
    ByteWriter out;
    out.put<std::uint8_t>(0);
    out.putVarint(4);
    out.putVarint(faces);
    for (float value : {0.0f, 0.0f, 0.0f, 1.0f}) out.put<float>(value);
    out.put<std::uint8_t>(16);
    const std::uint16_t corners[4][3] = {{0, 0, 0}, {65535, 0, 0}, {65535, 65535, 0}, {0, 65535, 0}};
    for (int axis = 0; axis < 3; ++axis)
        for (const auto& corner : corners) out.put<std::uint16_t>(corner[axis]);
    for (std::uint64_t f = 0; f < faces; ++f) out.putVarint(4);
    std::int64_t previous = 0;
    for (std::uint64_t f = 0; f < faces; ++f)
        for (int k = 0; k < 4; ++k) {
            out.putSigned(k - previous);
            previous = k;
        }
    for (int rule : {2, 1, 0, 0}) out.put<std::uint8_t>(std::uint8_t(rule));
    for (int tags = 0; tags < 3; ++tags) out.putVarint(0);
    return std::move(out.bytes());
}

void write(const std::filesystem::path& path, const Bytes& bytes) {
    std::ofstream file(path, std::ios::binary);
    file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!file) throw std::runtime_error(path.string() + ": could not write");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: subdfit_hostile_subd OUT_DIR\n");
        return 1;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    // 140 000 quads: 17.9 M triangles by default, past decode's 2^24.
    write(dir / "too_many_triangles.subd", container({{"CAGE", quadsCage(140000)}}));
    // A section claiming 4 GiB raw, and one claiming more than its frame holds.
    write(dir / "zstd_bomb.subd", container({{"CAGE", quadsCage(1), 0xFFFFFFFFu}}));
    write(dir / "raw_size_lie.subd", container({{"CAGE", quadsCage(1), 1u << 29}}));
    // The same cage, small: decodes (the files above fail for what they ask, not their form).
    write(dir / "one_quad.subd", container({{"CAGE", quadsCage(1)}}));
    return 0;
}
