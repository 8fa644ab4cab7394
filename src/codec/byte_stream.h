#pragma once
// Little-endian bytes for the .subd container (codec/subd_format.h): fixed-width integers,
// floats and LEB128 varints out, the same back in with every read bounds-checked, so a truncated
// or hostile file fails with one message instead of reading past its end.
#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "util/error.h"

namespace subdfit::codec {

// Data that ends before what it states: where a reader takes a file's first bytes (a prefix, as a
// stream delivers them), the one problem it forgives, by decoding less.
class TruncatedData : public Error {
public:
    using Error::Error;
};

class ByteWriter {
public:
    template <class T>
    void put(T value) {
        static_assert(std::endian::native == std::endian::little, "the .subd writer assumes a little-endian host");
        const auto* p = reinterpret_cast<const unsigned char*>(&value);
        bytes_.insert(bytes_.end(), p, p + sizeof(T));
    }
    void putVarint(std::uint64_t value) {
        do {
            const unsigned char low = value & 0x7f;
            value >>= 7;
            bytes_.push_back(low | (value ? 0x80 : 0));
        } while (value);
    }
    // Small signed values as small unsigned ones: 0, −1, 1, −2, ... → 0, 1, 2, 3, ...
    void putSigned(std::int64_t value) { putVarint((std::uint64_t(value) << 1) ^ std::uint64_t(value >> 63)); }
    void putBytes(std::span<const unsigned char> more) { bytes_.insert(bytes_.end(), more.begin(), more.end()); }

    std::vector<unsigned char>& bytes() { return bytes_; }

private:
    std::vector<unsigned char> bytes_;
};

class ByteReader {
public:
    // `what` names the data in errors ("asset.subd: CAGE section").
    ByteReader(std::span<const unsigned char> bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

    template <class T>
    T get() {
        T value;
        std::memcpy(&value, take(sizeof(T)).data(), sizeof(T));
        return value;
    }
    std::uint64_t getVarint() {
        std::uint64_t value = 0;
        for (int shift = 0; shift < 64; shift += 7) {
            const unsigned char byte = take(1)[0];
            value |= std::uint64_t(byte & 0x7f) << shift;
            if (!(byte & 0x80)) return value;
        }
        throw Error(what_ + ": malformed varint");
    }
    std::int64_t getSigned() {
        const std::uint64_t v = getVarint();
        return std::int64_t(v >> 1) ^ -std::int64_t(v & 1);
    }
    // An index below `limit`: refused, naming `what` ("crease vertex"), when it is not.
    int getIndex(std::uint64_t limit, const char* what) {
        const std::uint64_t v = getVarint();
        if (v >= limit) throw Error(what_ + ": " + what + " " + std::to_string(v) + " out of range");
        return int(v);
    }
    // A count of items that each take at least `minBytes`: refused before anything is allocated
    // when the rest of the data could not hold them.
    std::size_t getCount(std::size_t minBytes, const char* of) {
        const std::uint64_t n = getVarint();
        if (minBytes > 0 && n > remaining() / minBytes)
            throw Error(what_ + ": " + of + " count " + std::to_string(n) + " exceeds the data");
        return std::size_t(n);
    }
    std::span<const unsigned char> take(std::size_t n) {
        if (n > remaining()) throw TruncatedData(what_ + ": truncated");
        const auto part = bytes_.subspan(offset_, n);
        offset_ += n;
        return part;
    }
    std::size_t remaining() const { return bytes_.size() - offset_; }
    const std::string& what() const { return what_; }

private:
    std::span<const unsigned char> bytes_;
    std::size_t offset_ = 0;
    std::string what_;
};

}  // namespace subdfit::codec
