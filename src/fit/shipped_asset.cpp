#include "fit/shipped_asset.h"

#include "fit/fit_run.h"

namespace subdfit::fit {

render::ShadingModel shadingOf(const surface::SurfaceMaps& maps) {
    if (maps.hasMetallicRoughness()) return render::ShadingModel::MetallicRoughness;
    if (maps.hasBaseColor()) return render::ShadingModel::Lambert;
    return render::ShadingModel::Geometry;
}

surface::SurfaceMaps normalizedMaps(surface::SurfaceMaps maps, const scene::SceneFrame& frame) {
    for (float& height : maps.displacement) height *= frame.scale;
    return maps;
}

CageFitSettings drawingSettings(const surface::SurfaceMaps& maps, render::ShadingModel shading, int tessLevel) {
    CageFitSettings settings;
    // The maps it carries, of the appearance only what the shading draws.
    settings.mapEffects =
        maps.kinds() & (maps::MapEffects::on(kinds::MapLattice::Geometric) | maps::appearanceFor(shading));
    settings.shading = shading;
    settings.maps.resolution = std::max(1, maps.layout.resolution);
    settings.maps.appearanceResolution = std::max(1, maps.appearanceLayout.resolution);
    settings.maps.appearanceAtlas = maps.appearanceAtlas.size;
    settings.maps.shadingNormal = maps.shadingNormal;
    settings.tessLevel = std::max(tessLevel, maps.layout.resolution);
    return settings;
}

ShippedAsset::ShippedAsset(gl::ProgramCache& programs, const codec::SubdAsset& asset, const scene::SceneFrame& frame,
                           render::ShadingModel shading, int tessLevel)
    : programs_(programs), cage_(asset.cage), maps_(normalizedMaps(asset.maps, frame)), shading_(shading) {
    cage_.positions = frame.toNormalized(cage_.positions);
    build(tessLevel);
}

void ShippedAsset::setTessLevel(int level) { build(level); }

void ShippedAsset::build(int tessLevel) {
    fitter_ = std::make_unique<CageFitter>(programs_, cage_, drawingSettings(maps_, shading_, tessLevel));
    writeMaps(*fitter_, maps_);
}

}  // namespace subdfit::fit
