#include "export/subd_decode.h"

#include <new>

#include "export/surface_glb.h"
#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::exporter {

DecodeInput readForDecode(const std::filesystem::path& subd, const DensityRequest& request, DecodeBudget& budget,
                          int lods) {
    DecodeInput input;
    // The triangles to write are priced with the file, before its maps are built.
    input.asset = readSubd(subd, &budget, [&](const SubdOutline& outline) {
        input.density = pricedDensity(outline, request, budget, lods);
    });
    return input;
}

WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out,
                        const DensityRequest& request, MeshCoding coding) {
    io::checkOutputFile(out, subd);
    try {
        DecodeBudget budget(subd.string());
        const DecodeInput input = readForDecode(subd, request, budget);
        return writeSurfaceGlb(out, input.asset.cage, input.asset.maps, input.density.segments, coding);
    } catch (const std::bad_alloc&) {
        throw fileError(subd.string(), "out of memory while decoding it");
    }
}

}  // namespace subdfit::exporter
