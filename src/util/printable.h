#pragma once
// Text from a file, made fit to print: control bytes (an escape sequence would reach the terminal
// as it is) and bytes that are not UTF-8 become \xNN, and a long text is cut short, so that a
// hostile tag, keyword or name can neither drive the terminal nor flood a message.
#include <cstddef>
#include <string>
#include <string_view>

namespace subdfit {

std::string printable(std::string_view text, std::size_t maxBytes = 80);

// A library's message of several lines as one: its lines joined by "; " (ours are one line).
std::string oneLine(std::string_view text);

}  // namespace subdfit
