#include "export/usd/usdz_archive.h"

#include <zlib.h>

#include <cstdint>
#include <limits>
#include <set>

#include "codec/byte_stream.h"
#include "util/error.h"

namespace subdfit::exporter {
namespace {

constexpr std::uint32_t kLocalHeader = 0x04034b50, kCentralHeader = 0x02014b50, kEndOfDirectory = 0x06054b50;
constexpr std::uint16_t kVersion = 20;  // 2.0: what a stored entry needs
constexpr std::uint16_t kPaddingField = 0x1986;
constexpr std::uint16_t kDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01, 00:00: the archive is reproducible
constexpr std::size_t kLocalHeaderBytes = 30, kFieldHeaderBytes = 4;

struct Placed {
    std::uint32_t crc = 0, offset = 0;
};

void checkSize(std::size_t bytes) {
    if (bytes > std::numeric_limits<std::uint32_t>::max())
        throw Error("a .usdz past 4 GiB needs zip64, which this writer has not");
}

// The fields local and central headers share, from "version needed" to the extra field's length.
void putCommon(codec::ByteWriter& out, const UsdzEntry& entry, std::uint32_t crc, std::uint16_t extraBytes) {
    out.put<std::uint16_t>(kVersion);
    out.put<std::uint16_t>(0);  // flags
    out.put<std::uint16_t>(0);  // stored
    out.put<std::uint16_t>(0);  // time
    out.put<std::uint16_t>(kDate);
    out.put<std::uint32_t>(crc);
    out.put<std::uint32_t>(std::uint32_t(entry.bytes.size()));  // compressed = uncompressed
    out.put<std::uint32_t>(std::uint32_t(entry.bytes.size()));
    out.put<std::uint16_t>(std::uint16_t(entry.name.size()));
    out.put<std::uint16_t>(extraBytes);
}

}  // namespace

std::vector<unsigned char> usdzArchive(std::span<const UsdzEntry> entries) {
    if (entries.empty()) throw Error("a .usdz needs at least its root layer");
    if (entries.size() > 0xffff) throw Error("a .usdz of over 65 535 entries needs zip64, which this writer has not");
    std::set<std::string> names;
    for (const UsdzEntry& entry : entries) {
        if (entry.name.empty() || entry.name.size() > 0xffff || !names.insert(entry.name).second)
            throw Error("a .usdz entry's name is empty, too long or repeated: '" + entry.name + "'");
        checkSize(entry.bytes.size());
    }
    codec::ByteWriter out;
    std::vector<Placed> placed;
    for (const UsdzEntry& entry : entries) {
        const std::size_t offset = out.bytes().size();
        const std::size_t unpadded = offset + kLocalHeaderBytes + entry.name.size() + kFieldHeaderBytes;
        const std::size_t padding = (kUsdzAlignment - unpadded % kUsdzAlignment) % kUsdzAlignment;
        const auto crc = std::uint32_t(crc32(crc32(0L, Z_NULL, 0), entry.bytes.data(), uInt(entry.bytes.size())));
        checkSize(offset);
        placed.push_back({crc, std::uint32_t(offset)});
        out.put<std::uint32_t>(kLocalHeader);
        putCommon(out, entry, crc, std::uint16_t(kFieldHeaderBytes + padding));
        out.putBytes({reinterpret_cast<const unsigned char*>(entry.name.data()), entry.name.size()});
        out.put<std::uint16_t>(kPaddingField);
        out.put<std::uint16_t>(std::uint16_t(padding));
        out.bytes().resize(out.bytes().size() + padding, 0);
        SUBDFIT_CHECK(out.bytes().size() % kUsdzAlignment == 0);
        out.putBytes(entry.bytes);
    }
    const std::size_t directory = out.bytes().size();
    for (std::size_t k = 0; k < entries.size(); ++k) {
        out.put<std::uint32_t>(kCentralHeader);
        out.put<std::uint16_t>(kVersion);  // made by
        putCommon(out, entries[k], placed[k].crc, 0);
        out.put<std::uint16_t>(0);  // comment
        out.put<std::uint16_t>(0);  // disk
        out.put<std::uint16_t>(0);  // internal attributes
        out.put<std::uint32_t>(0);  // external attributes
        out.put<std::uint32_t>(placed[k].offset);
        out.putBytes({reinterpret_cast<const unsigned char*>(entries[k].name.data()), entries[k].name.size()});
    }
    const std::size_t end = out.bytes().size();
    checkSize(end);
    out.put<std::uint32_t>(kEndOfDirectory);
    out.put<std::uint16_t>(0);
    out.put<std::uint16_t>(0);
    out.put<std::uint16_t>(std::uint16_t(entries.size()));
    out.put<std::uint16_t>(std::uint16_t(entries.size()));
    out.put<std::uint32_t>(std::uint32_t(end - directory));
    out.put<std::uint32_t>(std::uint32_t(directory));
    out.put<std::uint16_t>(0);  // comment
    return std::move(out.bytes());
}

}  // namespace subdfit::exporter
