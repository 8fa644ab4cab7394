// Writes tests/data/hostile-subd/: small .subd files that state far more than they hold (see the
// README there). Build and run from the repository root, after building subdfit:
//   g++ -std=c++20 -Isrc -Itests/support tests/data/tools/make_hostile_subd.cpp build/src/libsubdfit_util.a -lzstd -lxxhash \
//       -o /tmp/make_hostile_subd && /tmp/make_hostile_subd tests/data/hostile-subd
#include <zstd.h>

#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "codec/byte_stream.h"
#include "subd_bytes.h"
#include "util/hash.h"

using namespace subdfit;
using namespace subdfit::codec;
using Bytes = std::vector<unsigned char>;

// A displacement section of resolution T stating `nodes` nodes, all residuals zero.
Bytes heights(std::uint64_t T, std::uint64_t nodes, std::uint64_t zeros) {
    ByteWriter out;
    out.putVarint(T);
    out.putVarint(nodes);
    out.put<float>(0.0f);
    out.put<float>(0.01f);
    out.put<std::uint8_t>(0);
    out.put<std::uint8_t>(0);
    for (std::uint64_t k = 0; k < zeros; ++k) out.put<std::uint8_t>(0);
    return std::move(out.bytes());
}

void write(const std::string& path, const std::vector<std::pair<const char*, Bytes>>& sections,
           std::uint32_t padTo = 0) {
    ByteWriter file;
    file.putBytes({reinterpret_cast<const unsigned char*>("SUBD"), 4});
    file.put<std::uint16_t>(5);
    file.put<std::uint16_t>(0);
    file.put<std::uint32_t>(std::uint32_t(sections.size()));
    for (const auto& [tag, raw] : sections) {
        Bytes stored(ZSTD_compressBound(raw.size()));
        stored.resize(ZSTD_compress(stored.data(), stored.size(), raw.data(), raw.size(), 19));
        file.putBytes({reinterpret_cast<const unsigned char*>(tag), 4});
        file.put<std::uint32_t>(std::uint32_t(stored.size()));
        file.put<std::uint32_t>(std::uint32_t(raw.size()));
        file.putBytes(stored);
    }
    const auto& bytes = file.bytes();
    file.put<std::uint64_t>(hash64({reinterpret_cast<const char*>(bytes.data()), bytes.size()}));
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(file.bytes().data()), std::streamsize(file.bytes().size()));
}

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : ".";
    write(dir + "/plain_90k_quads.subd", {{"CAGE", test::plainGridCage(300)}});
    write(dir + "/plain_2m_quads.subd", {{"CAGE", test::plainGridCage(1415)}});
    write(dir + "/one_node_at_resolution_64.subd", {{"CAGE", test::plainGridCage(141)}, {"DISP", heights(64, 1, 64)}});
    const std::uint64_t side = 1000 * 2 + 1;
    write(dir + "/heights_on_1m_faces.subd",
          {{"CAGE", test::plainGridCage(1000)}, {"DISP", heights(2, side * side, side * side)}});
    Bytes bomb = test::plainGridCage(2);
    bomb.resize(bomb.size() + (std::size_t(60) << 20), 0);  // within the section limit, far beyond a 4-face cage
    write(dir + "/zstd_bomb.subd", {{"CAGE", bomb}});
    return 0;
}
