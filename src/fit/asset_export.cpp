#include "fit/asset_export.h"

#include "export/glb_writer.h"
#include "export/limit_tessellation.h"
#include "export/map_atlas.h"

namespace subdfit::fit {

nlohmann::json exportAsset(const FitOptions& o, CageFitter& fitter, const scene::SceneFrame& frame,
                           const mesh::PolygonMesh& fittedWorld) {
    exporter::FittedMaps maps;
    std::vector<exporter::WrittenFile> written;
    std::vector<unsigned char> normalPng;
    if (auto* parameters = fitter.maps()) {
        maps.layout = parameters->layout();
        if (auto* g = parameters->displacement()) {
            maps.displacement = g->read();
            for (float& d : maps.displacement) d /= frame.scale;  // heights back to world units
        }
        if (auto* g = parameters->normalMap()) maps.normal = g->read();
        written = exporter::writeMapAtlases(o.out, maps, {.compact = o.compactMaps});
        if (maps.hasNormal()) normalPng = exporter::encodeNormalPng(exporter::atlasLayout(maps.layout), maps);
    } else {
        maps.layout = maps::buildTexelLayout(fittedWorld, 1);  // no maps: UVs still name each face's tile
    }
    const auto tessellation = exporter::tessellateLimitSurface(fittedWorld, maps, fitter.renderer().tessLevel());
    written.push_back(exporter::writeFittedGlb(o.out / "fitted.glb", tessellation, normalPng, o.draco));
    nlohmann::json files = nlohmann::json::object();
    for (const auto& file : written) files[file.path.filename().string()] = file.bytes;
    return files;
}

}  // namespace subdfit::fit
