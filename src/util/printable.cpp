#include "util/printable.h"

#include <cstdio>

namespace subdfit {
namespace {

// The length of the well-formed UTF-8 sequence at the start of `s` that encodes a printable
// code point, or 0 (C1 controls, U+0080..U+009F, are controls too).
std::size_t printableSequence(std::string_view s) {
    const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char lead = byte(0);
    std::size_t length = lead >= 0xF0 && lead <= 0xF4 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC2 && lead < 0xE0 ? 2 : 0;
    if (length == 0 || s.size() < length) return 0;
    for (std::size_t k = 1; k < length; ++k)
        if ((byte(k) & 0xC0) != 0x80) return 0;
    if (lead == 0xC2 && byte(1) < 0xA0) return 0;   // C1 controls
    if (lead == 0xE0 && byte(1) < 0xA0) return 0;   // overlong
    if (lead == 0xED && byte(1) >= 0xA0) return 0;  // surrogates
    if (lead == 0xF0 && byte(1) < 0x90) return 0;   // overlong
    if (lead == 0xF4 && byte(1) >= 0x90) return 0;  // beyond U+10FFFF
    return length;
}

}  // namespace

std::string printable(std::string_view text, std::size_t maxBytes) {
    std::string out;
    std::size_t k = 0;
    while (k < text.size() && out.size() < maxBytes) {
        const unsigned char c = static_cast<unsigned char>(text[k]);
        if (c >= 0x20 && c < 0x7F) {
            out += char(c);
            ++k;
        } else if (const std::size_t n = c >= 0x80 ? printableSequence(text.substr(k)) : 0; n > 0) {
            out.append(text.substr(k, n));
            k += n;
        } else {
            char escaped[5];
            std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
            out += escaped;
            ++k;
        }
    }
    if (k < text.size()) out += "...";
    return out;
}

std::string oneLine(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '\n' || c == '\r') {
            if (!out.empty() && out.back() != ' ') out += "; ";
        } else {
            out += c;
        }
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == ';')) out.pop_back();
    return out.empty() ? "unknown error" : out;
}

}  // namespace subdfit
