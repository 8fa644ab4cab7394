#include "export/engine/subd_decode.h"

#include <new>

#include "export/gltf/surface_glb.h"
#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::exporter {

DecodeInput readForDecode(const std::filesystem::path& subd, const codec::DensityRequest& request,
                          codec::DecodeBudget& budget, int lods, std::size_t firstBytes) {
    DecodeInput input;
    // The triangles to write are priced with the file, before its maps are built.
    input.asset = codec::readSubd(
        subd, &budget,
        [&](const codec::SubdOutline& outline) {
            input.density = codec::pricedDensity(outline, request, budget, lods);
        },
        firstBytes);
    return input;
}

io::WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out,
                            const codec::DensityRequest& request, MeshCoding coding) {
    io::checkOutputFile(out, subd);
    try {
        codec::DecodeBudget budget(subd.string());
        const DecodeInput input = readForDecode(subd, request, budget);
        return writeSurfaceGlb(out, input.asset.cage, input.asset.maps, input.density.segments, coding);
    } catch (const std::bad_alloc&) {
        throw fileError(subd.string(), "out of memory while decoding it");
    }
}

}  // namespace subdfit::exporter
