#pragma once
// `decode --max-error`: a distance in the asset's units ("0.002"), or a percentage of its
// bounding box diagonal ("0.1%"); positive and finite. Anything else is refused with `problem`
// saying why, so that a bad bound is one kind of error.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <string>

#include "export/engine/error_density.h"

namespace subdfit::apps {

inline std::optional<exporter::ErrorBound> parseErrorBound(const std::string& text, std::string& problem) {
    const bool percent = !text.empty() && text.back() == '%';
    const std::string number = percent ? text.substr(0, text.size() - 1) : text;
    char* end = nullptr;
    errno = 0;
    const double value =
        number.empty() || std::isspace(static_cast<unsigned char>(number[0])) ? 0.0 : std::strtod(number.c_str(), &end);
    if (number.empty() || end != number.c_str() + number.size() || errno != 0 || !std::isfinite(value) ||
        !(value > 0.0)) {
        problem =
            "must be a positive distance in the asset's units, or a percentage of its bounding box diagonal (0.002, "
            "0.1%), got '" +
            text + "'";
        return std::nullopt;
    }
    return exporter::ErrorBound{.value = percent ? value / 100.0 : value, .ofDiagonal = percent};
}

}  // namespace subdfit::apps
