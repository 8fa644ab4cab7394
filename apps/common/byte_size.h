#pragma once
// Byte sizes on the command line (`--budget`): decimal digits with an optional fraction and an
// optional unit, nothing else ("0x100", "1e3", "-5", " 20" are refused, not read by strtod's
// rules). K, M, G, T are powers of 1000 (a trailing B allowed), KiB, MiB, GiB, TiB of 1024;
// case does not matter. The range is checked here too, so that a bad size is one kind of error.
#include <cctype>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

namespace subdfit::apps {

inline constexpr double kLeastByteSize = 100.0, kMostByteSize = 1e12;  // 100 bytes to 1 TB

// The size, or nothing when `text` is not one within 100 bytes .. 1 TB; `problem` says why.
inline std::optional<std::uintmax_t> parseByteSize(const std::string& text, std::string& problem) {
    size_t k = 0, digits = 0;
    std::string number;
    while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) number += text[k++], ++digits;
    if (k < text.size() && text[k] == '.') {
        number += text[k++];
        while (k < text.size() && std::isdigit(static_cast<unsigned char>(text[k]))) number += text[k++], ++digits;
    }
    std::string unit;
    for (; k < text.size(); ++k) unit += char(std::toupper(static_cast<unsigned char>(text[k])));
    double scale = 0.0;
    if (unit.empty() || unit == "B") scale = 1.0;
    else if (unit == "K" || unit == "KB") scale = 1e3;
    else if (unit == "M" || unit == "MB") scale = 1e6;
    else if (unit == "G" || unit == "GB") scale = 1e9;
    else if (unit == "T" || unit == "TB") scale = 1e12;
    else if (unit == "KIB") scale = 1024.0;
    else if (unit == "MIB") scale = 1024.0 * 1024.0;
    else if (unit == "GIB") scale = 1024.0 * 1024.0 * 1024.0;
    else if (unit == "TIB") scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
    if (digits == 0 || scale == 0.0 || number.size() > 30) {
        problem = "must be bytes: digits with an optional K, M, G or T (20000, 20KB, 1.5MB), got '" + text + "'";
        return std::nullopt;
    }
    const double bytes = std::stod(number) * scale;
    if (!(bytes >= kLeastByteSize && bytes <= kMostByteSize)) {
        problem = "must be 100 bytes to 1 TB, got '" + text + "'";
        return std::nullopt;
    }
    return std::uintmax_t(std::llround(bytes));
}

}  // namespace subdfit::apps
