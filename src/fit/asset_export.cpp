#include "fit/asset_export.h"

#include "export/glb_writer.h"
#include "export/gltf_mesh.h"
#include "export/map_atlas.h"
#include "export/subd_format.h"
#include "surface/tessellation.h"

namespace subdfit::fit {

nlohmann::json exportAsset(const FitOptions& o, CageFitter& fitter, const scene::SceneFrame& frame,
                           const mesh::PolygonMesh& fittedWorld) {
    surface::SurfaceMaps maps = fitter.surfaceMaps();
    for (float& d : maps.displacement) d /= frame.scale;  // heights back to world units
    std::vector<exporter::WrittenFile> written;
    std::vector<unsigned char> normalPng;
    if (fitter.maps()) {
        written = exporter::writeMapAtlases(o.out, maps, {.compact = o.compactMaps});
        if (maps.hasNormal()) normalPng = exporter::encodeNormalPng(exporter::atlasLayout(maps.layout), maps);
    }
    // Without maps the texcoords still name each face's tile, on a one-cell layout.
    const auto atlas = exporter::atlasLayout(fitter.maps() ? maps.layout : surface::buildTexelLayout(fittedWorld, 1));
    const auto tessellation = surface::tessellate(fittedWorld, maps, fitter.renderer().tessLevel());
    written.push_back(
        exporter::writeFittedGlb(o.out / "fitted.glb", exporter::gltfMesh(tessellation, atlas), normalPng, o.draco));
    written.push_back(exporter::writeSubd(o.out / "asset.subd", exporter::shippableAsset(fittedWorld, maps)));
    nlohmann::json files = nlohmann::json::object();
    for (const auto& file : written) files[file.path.filename().string()] = file.bytes;
    return files;
}

}  // namespace subdfit::fit
