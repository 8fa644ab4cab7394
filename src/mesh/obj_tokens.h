#pragma once
// Tokenising and number parsing for the OBJ reader and its `t` tags. Lines are views into the
// whole-file buffer; numbers go through std::from_chars (no locale, no allocation).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "util/error.h"

namespace subdfit::mesh::obj {

// Where a problem is, for "path: line N: problem".
struct LineContext {
    const std::string& path;
    int line = 0;
    [[noreturn]] void fail(const std::string& problem) const {
        throw fileError(path, "line " + std::to_string(line) + ": " + problem);
    }
};

inline bool isSpace(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Whitespace-separated tokens of one line.
class Tokens {
public:
    explicit Tokens(std::string_view line) : rest_(line) {}
    // The next token, or an empty view at the end of the line.
    std::string_view next() {
        size_t i = 0;
        while (i < rest_.size() && isSpace(rest_[i])) ++i;
        size_t j = i;
        while (j < rest_.size() && !isSpace(rest_[j])) ++j;
        const std::string_view token = rest_.substr(i, j - i);
        rest_.remove_prefix(j);
        return token;
    }

private:
    std::string_view rest_;
};

// The rest of a line after its keyword, trimmed: names (files, materials) may contain spaces.
inline std::string_view restOfLine(std::string_view line, std::string_view keyword) {
    line.remove_prefix(std::min(line.size(), line.find(keyword) + keyword.size()));
    while (!line.empty() && isSpace(line.front())) line.remove_prefix(1);
    while (!line.empty() && isSpace(line.back())) line.remove_suffix(1);
    return line;
}

// A token quoted for an error message, cut short so that a binary file cannot flood it.
inline std::string quoted(std::string_view token) {
    constexpr size_t kMax = 24;
    std::string s(token.substr(0, kMax));
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) c = '?';
    return "'" + s + (token.size() > kMax ? "...'" : "'");
}

// from_chars rejects a leading '+', which some exporters write.
inline const char* skipPlus(const char* first, const char* last) {
    return (first != last && *first == '+' && first + 1 != last && first[1] != '-') ? first + 1 : first;
}

// Parses the whole token as a float (NaN and Inf parse; the caller decides about them).
inline bool parseFloat(std::string_view token, float& value) {
    const char* first = skipPlus(token.data(), token.data() + token.size());
    const char* last = token.data() + token.size();
    if (first == last) return false;
    const auto [ptr, ec] = std::from_chars(first, last, value);
    if (ptr != last) return false;
    if (ec == std::errc()) return true;
    if (ec != std::errc::result_out_of_range) return false;
    // Out of range is both overflow (an error) and underflow (a tiny value that is fine as
    // a subnormal or zero); strtod tells them apart.
    std::string copy(first, last);
    const double d = std::strtod(copy.c_str(), nullptr);
    if (!(std::fabs(d) < 1.0)) return false;
    value = float(d);
    return true;
}

// Parses a leading integer of the token; `end` receives where it stopped.
inline bool parseIntPrefix(std::string_view token, int64_t& value, const char*& end) {
    const char* first = skipPlus(token.data(), token.data() + token.size());
    const char* last = token.data() + token.size();
    const auto [ptr, ec] = std::from_chars(first, last, value);
    end = ptr;
    return ec == std::errc() && ptr != first;
}

inline bool parseInt(std::string_view token, int64_t& value) {
    const char* end = nullptr;
    return parseIntPrefix(token, value, end) && end == token.data() + token.size();
}

}  // namespace subdfit::mesh::obj
