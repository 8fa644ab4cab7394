#pragma once
// `subdfit decode` as engines want it: the density by default, from --triangles / --tess, or
// from an error bound (--max-error, error_density.h); optionally a chain of levels of detail
// (--lods, lod_chain.h) described in a JSON beside them; every mesh quantised
// (KHR_mesh_quantization, which every glTF reader opens), meshopt-compressed where the caller
// asks, or floats (export/gltf/glb_writer.h MeshCoding).
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "codec/decode_density.h"
#include "export/engine/error_density.h"
#include "export/engine/lod_chain.h"
#include "export/gltf/glb_writer.h"
#include "io/output_file.h"

namespace subdfit::exporter {

struct EngineDecodeOptions {
    codec::DensityRequest density{};       // --triangles / --tess; 0: the default
    std::optional<ErrorBound> maxError{};  // --max-error, instead of `density`
    int lods = 0;                          // --lods K: K files and the JSON; 0: one file, no JSON
    MeshCoding coding = MeshCoding::Quantized;
    ScreenSizeRule screenSize{};
    // --bytes N: only the file's first N bytes, as a stream delivers them (codec::SubdEnding::Prefix)
    std::size_t firstBytes = std::numeric_limits<std::size_t>::max();
};

// `out` is level 0; level k (k >= 1) goes to `<stem>_lod<k>.glb` beside it, and with --lods the
// JSON to `<stem>_lods.json`. Every mesh is built and encoded before the first file is written
// (each atomically). Throws subdfit::Error as decodeToGlb (export/engine/subd_decode.h), and for an
// error bound that is not positive.
std::vector<io::WrittenFile> decodeForEngines(const std::filesystem::path& subd, const std::filesystem::path& out,
                                              const EngineDecodeOptions& options);

// Where level `k` of `out` goes, and the JSON.
std::filesystem::path lodPath(const std::filesystem::path& out, int k);
std::filesystem::path lodJsonPath(const std::filesystem::path& out);

}  // namespace subdfit::exporter
