#include "simplify/compare/quality.h"

#include "codec/subd_format.h"
#include "fit/fit_run.h"
#include "fit/fit_scene.h"
#include "fit/image_metrics.h"
#include "surface/tessellation.h"

namespace subdfit::simplify {

nlohmann::json toJson(const Quality& q) {
    // A distance the run did not measure says so, rather than a 0 that reads as a perfect one.
    auto measured = [&](double geometry::SurfaceDistance::*field) -> nlohmann::json {
        return q.distance ? nlohmann::json((*q.distance).*field) : nlohmann::json(kNotMeasured);
    };
    nlohmann::json j = {{"psnr_holdout", q.psnrHoldout},
                        {"ssim_holdout", q.ssimHoldout},
                        {"psnr_holdout_views", q.psnrViews},
                        {"chamfer", measured(&geometry::SurfaceDistance::chamferL2Squared)},
                        {"hausdorff", measured(&geometry::SurfaceDistance::hausdorff)},
                        {"mean_distance", measured(&geometry::SurfaceDistance::meanDistance)},
                        {"bytes", q.bytes},
                        {"files", q.files}};
    if (!q.shipped.empty()) j["path"] = q.shipped.generic_string();
    j.update(q.details);
    return j;
}

std::uintmax_t totalBytes(const nlohmann::json& files) {
    std::uintmax_t total = 0;
    for (const auto& [name, bytes] : files.items()) total += bytes.get<std::uintmax_t>();
    return total;
}

void setHoldout(const fit::HoldoutScore& score, Quality& quality) {
    quality.psnrHoldout = score.psnr;
    quality.ssimHoldout = score.ssim;
    quality.psnrViews = score.psnrViews;
    quality.view = score.firstView;
}

void scoreHoldout(const scene::TargetSet& holdout, const DrawFunction& draw, Quality& quality) {
    setHoldout(fit::scoreHoldout(holdout, draw), quality);
}

std::unique_ptr<fit::CageFitter> drawnAsFitted(gl::ProgramCache& programs, const fit::FitScene& scene,
                                               const codec::SubdAsset& shipped, int tessLevel) {
    mesh::PolygonMesh cage = shipped.cage;
    cage.positions = scene.frame.toNormalized(cage.positions);
    surface::SurfaceMaps maps = shipped.maps;
    for (float& d : maps.displacement) d *= scene.frame.scale;
    fit::CageFitSettings rendering;
    rendering.shading = scene.shading;
    rendering.mapEffects = maps.kinds();
    rendering.maps.resolution = std::max(maps.layout.resolution, 1);
    rendering.maps.appearanceResolution = std::max(maps.appearanceLayout.resolution, 1);
    rendering.maps.appearanceAtlas = maps.appearanceAtlas.size;
    rendering.maps.shadingNormal = maps.shadingNormal;
    if (tessLevel > 0) rendering.tessLevel = tessLevel;
    auto fitter = std::make_unique<fit::CageFitter>(programs, cage, rendering);
    fit::writeMaps(*fitter, maps);
    return fitter;
}

geometry::SurfaceDistance worldDistance(const mesh::PolygonMesh& candidate, const mesh::PolygonMesh& reference,
                                        const scene::SceneFrame& frame, int samples) {
    geometry::SurfaceDistance d = geometry::surfaceDistance(candidate, reference, samples);
    d.chamferL2Squared /= double(frame.scale) * double(frame.scale);
    d.meanDistance /= double(frame.scale);
    d.hausdorff /= double(frame.scale);
    return d;
}

geometry::SurfaceDistance shippedDistance(const std::filesystem::path& subd, int segments,
                                          const scene::SceneFrame& frame, const mesh::PolygonMesh& reference,
                                          int samples) {
    const codec::SubdAsset shipped = codec::readSubd(subd);
    mesh::PolygonMesh surface = surface::triangleMesh(surface::tessellate(shipped.cage, shipped.maps, segments));
    surface.positions = frame.toNormalized(surface.positions);
    return worldDistance(surface, reference, frame, samples);
}

}  // namespace subdfit::simplify
