#include "simplify/compare/quality.h"

#include "export/subd_format.h"
#include "fit/image_metrics.h"
#include "surface/tessellation.h"

namespace subdfit::simplify {

nlohmann::json toJson(const Quality& q) {
    nlohmann::json j = {{"psnr_holdout", q.psnrHoldout},
                        {"ssim_holdout", q.ssimHoldout},
                        {"psnr_holdout_views", q.psnrViews},
                        {"chamfer", q.distance.chamferL2Squared},
                        {"hausdorff", q.distance.hausdorff},
                        {"mean_distance", q.distance.meanDistance},
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

void scoreHoldout(const scene::TargetSet& holdout, const DrawFunction& draw, Quality& quality) {
    double loss = 0.0, similarity = 0.0;
    quality.psnrViews.clear();
    for (int i = 0; i < holdout.size(); ++i) {
        auto pixels = holdout.render(i, draw);  // as the targets were made (anti-aliased)
        const auto target = holdout.readColor(i);
        const double viewLoss = fit::meanPixelLoss(pixels, target);
        loss += viewLoss;
        quality.psnrViews.push_back(fit::psnrFromLoss(viewLoss));
        similarity += fit::structuralSimilarity(pixels, target, holdout.resolution(), holdout.resolution());
        if (i == 0) quality.view = std::move(pixels);
    }
    quality.psnrHoldout = fit::psnrFromLoss(loss / std::max(1, holdout.size()));
    quality.ssimHoldout = holdout.size() > 0 ? similarity / holdout.size() : 0.0;
}

geometry::SurfaceDistance worldDistance(const mesh::PolygonMesh& candidate, const mesh::PolygonMesh& reference,
                                        const scene::SceneFrame& frame, int samples) {
    geometry::SurfaceDistance d = geometry::surfaceDistance(candidate, reference, samples);
    d.chamferL2Squared /= double(frame.scale) * double(frame.scale);
    d.meanDistance /= double(frame.scale);
    d.hausdorff /= double(frame.scale);
    return d;
}

geometry::SurfaceDistance shippedDistance(const std::filesystem::path& subd, int segments, const scene::SceneFrame& frame,
                                          const mesh::PolygonMesh& reference, int samples) {
    const exporter::SubdAsset shipped = exporter::readSubd(subd);
    mesh::PolygonMesh surface = surface::triangleMesh(surface::tessellate(shipped.cage, shipped.maps, segments));
    surface.positions = frame.toNormalized(surface.positions);
    return worldDistance(surface, reference, frame, samples);
}

}  // namespace subdfit::simplify
