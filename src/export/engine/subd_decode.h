#pragma once
// `subdfit decode`: a shipped .subd file back to what any glTF viewer or engine reads, the
// displaced limit surface as triangles (with the normal map, if the file has one, as the
// material's normalTexture), as densely as codec/decode_density.h chooses. Reads nothing but the
// file; what it decodes and writes is priced against one budget (codec/decode_budget.h) before
// it is allocated; `out` is written only over a regular file (or where nothing is). The LOD chain
// and the density from an error bound are export/engine/engine_decode.h's.
#include <filesystem>
#include <limits>

#include "codec/decode_budget.h"
#include "codec/decode_density.h"
#include "export/gltf/glb_writer.h"
#include "io/output_file.h"
#include "codec/subd_format.h"

namespace subdfit::exporter {

// A .subd read for decoding (only its first `firstBytes`, where that is fewer: a prefix): the
// asset, and the density `request` gets, whose triangles (and `lods` levels of detail from them:
// codec::pricedDensity) were priced in `budget` with the file's counts before the maps were built.
struct DecodeInput {
    codec::SubdAsset asset;
    codec::DecodeDensity density;
};
DecodeInput readForDecode(const std::filesystem::path& subd, const codec::DensityRequest& request,
                          codec::DecodeBudget& budget, int lods = 1,
                          std::size_t firstBytes = std::numeric_limits<std::size_t>::max());

// Writes `out` (.glb) atomically, its mesh stored as `coding` says. Throws subdfit::Error naming
// the file for a bad input, an impossible density or an output that may not be written (empty,
// the input itself, a folder, anything but a regular file), before any work.
io::WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out,
                            const codec::DensityRequest& request = {}, MeshCoding coding = MeshCoding::Quantized);

}  // namespace subdfit::exporter
