#pragma once
// JSON as subdfit writes it (reports, statuses, glTF documents): bytes of a name that are not
// UTF-8 (a file name from a Latin-1 folder, a material name from an old OBJ) become U+FFFD
// instead of making nlohmann::json throw mid-write with no file named.
#include <string>

#include <nlohmann/json.hpp>

namespace subdfit {

// `indent` < 0: compact; else pretty-printed with a newline at the end.
inline std::string jsonText(const nlohmann::json& value, int indent = -1) {
    std::string text = value.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
    if (indent >= 0) text += "\n";
    return text;
}

}  // namespace subdfit
