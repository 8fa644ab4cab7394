#pragma once
// The GLB container of glTF 2.0 (spec section 4.4): a 12-byte header, a JSON chunk padded with
// spaces, and an optional BIN chunk padded with zeros, every chunk 4-byte aligned.
#include <span>
#include <vector>

#include <nlohmann/json.hpp>

namespace subdfit::exporter {

// The whole file's bytes. `binary` is the single buffer the document's buffers[0] describes.
// Throws subdfit::Error when the result would exceed GLB's 4 GiB limit.
std::vector<unsigned char> packGlb(const nlohmann::json& document, std::span<const unsigned char> binary);

}  // namespace subdfit::exporter
