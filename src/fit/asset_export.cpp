#include "fit/asset_export.h"

#include <algorithm>

#include "codec/map_atlas.h"
#include "export/map_images.h"
#include "codec/subd_format.h"
#include "export/gltf/surface_glb.h"
#include "export/usd/usd_export.h"

namespace subdfit::fit {

namespace {

surface::SurfaceMaps worldMaps(CageFitter& fitter, const scene::SceneFrame& frame) {
    surface::SurfaceMaps maps = fitter.surfaceMaps();
    for (float& d : maps.displacement) d /= frame.scale;  // heights back to world units
    return maps;
}

}  // namespace

codec::SubdPrecision subdPrecision(const FitOptions& o) {
    return codec::SubdPrecision::forMapBits(o.mapBits, o.appearanceQuality, o.positionBits);
}

codec::SubdAsset shippableState(const FitOptions& o, CageFitter& fitter, const scene::SceneFrame& frame,
                                const mesh::PolygonMesh& fittedWorld, std::uint32_t referenceTriangles) {
    return codec::shippableAsset(fittedWorld, worldMaps(fitter, frame), o.positionBits, referenceTriangles);
}

nlohmann::json exportAsset(const FitOptions& o, CageFitter& fitter, const scene::SceneFrame& frame,
                           const mesh::PolygonMesh& fittedWorld, std::uint32_t referenceTriangles) {
    const surface::SurfaceMaps maps = worldMaps(fitter, frame);
    std::vector<io::WrittenFile> written;
    if (fitter.maps()) written = exporter::writeMapAtlases(o.out, maps, {.compact = o.compactMaps});
    if (o.preview)
        written.push_back(
            exporter::writeSurfaceGlb(o.out / "fitted.glb", fittedWorld, maps, fitter.renderer().tessLevel(), o.draco));
    const codec::SubdPrecision precision = subdPrecision(o);
    written.push_back(codec::writeSubd(
        o.out / "asset.subd", codec::shippableAsset(fittedWorld, maps, precision.positionBits, referenceTriangles),
        precision));
    nlohmann::json files = nlohmann::json::object();
    for (const auto& file : written) files[file.path.filename().string()] = file.bytes;
    files.update(exportUsd(o, o.out));
    return files;
}

nlohmann::json exportUsd(const FitOptions& o, const std::filesystem::path& dir) {
    nlohmann::json files = nlohmann::json::object();
    if (o.usd == UsdExport::None) return files;
    const auto written = exporter::writeUsd(dir, codec::readSubd(dir / "asset.subd"), o.usd == UsdExport::UsdzAndUsda);
    for (const auto& file : written) files[file.path.filename().string()] = file.bytes;
    return files;
}

}  // namespace subdfit::fit
