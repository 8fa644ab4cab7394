#pragma once
// `subdfit decode`: a shipped .subd file back to what any glTF viewer or engine reads, the
// displaced limit surface as triangles (with the normal map, if the file has one, as the
// material's normalTexture). Reads nothing but the file.
#include <filesystem>

#include "export/output_file.h"
#include "export/subd_format.h"

namespace subdfit::exporter {

// The segments per ptex-face edge decode uses by default: one vertex per map node (the
// density the maps were sampled at), or 8 without maps.
int defaultDecodeSegments(const SubdAsset& asset);

// Writes `out` (.glb) atomically; segments 0: the default. Throws subdfit::Error naming the
// file for a bad input or an impossible tessellation.
WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out, int segments = 0);

}  // namespace subdfit::exporter
