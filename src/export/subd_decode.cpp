#include "export/subd_decode.h"

#include <new>

#include "export/decode_budget.h"
#include "export/surface_glb.h"
#include "io/atomic_file.h"
#include "util/error.h"

namespace subdfit::exporter {

WrittenFile decodeToGlb(const std::filesystem::path& subd, const std::filesystem::path& out, const DensityRequest& request) {
    io::checkOutputFile(out, subd);
    try {
        DecodeBudget budget(subd.string());
        DecodeDensity density;
        // The triangles to write are priced with the file, before its maps are built.
        const SubdAsset asset = readSubd(subd, &budget, [&](const SubdOutline& outline) {
            density = pricedDensity(outline, request, budget);
        });
        return writeSurfaceGlb(out, asset.cage, asset.maps, density.segments, false);
    } catch (const std::bad_alloc&) {
        throw fileError(subd.string(), "out of memory while decoding it");
    }
}

}  // namespace subdfit::exporter
