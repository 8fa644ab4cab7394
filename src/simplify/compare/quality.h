#pragma once
// How good a simplified asset is, measured the same way for subdfit and for each baseline:
// PSNR and SSIM over the held-out views, surface distance to the reference, and the bytes a user
// ships.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <glm/vec4.hpp>
#include <nlohmann/json.hpp>

#include "codec/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_report.h"
#include "fit/fit_scene.h"
#include "geometry/surface_distance.h"
#include "gl/program_cache.h"
#include "render/camera.h"
#include "render/render_target.h"
#include "scene/scene_frame.h"
#include "scene/target_set.h"
#include "surface/surface_maps.h"

namespace subdfit::simplify {

struct Quality {
    double psnrHoldout = 0.0;
    double ssimHoldout = 0.0;  // mean over the held-out views (fit/image_metrics.h)
    // Each held-out view's own PSNR: psnrHoldout is of their mean loss, so one bad view can
    // decide it, and this says which.
    std::vector<double> psnrViews;
    // In the reference's units; none where the run measured no distance (--compare none, fast).
    std::optional<geometry::SurfaceDistance> distance;
    std::uintmax_t bytes = 0;
    nlohmann::json files = nlohmann::json::object();  // {shipped file: bytes}
    // The file a consumer opens (a .glb, or the asset.subd), relative to the output folder:
    // report.json's `path`, what a viewer shows. Empty: not said.
    std::filesystem::path shipped;
    nlohmann::json details = nlohmann::json::object();  // what else the report should say
    std::vector<glm::vec4> view;                        // held-out view 0 as rendered, for the side-by-side
};

// What report.json and the terminal say for a distance a run did not measure.
inline constexpr const char* kNotMeasured = "not measured";

nlohmann::json toJson(const Quality& quality);

// The sum of a {file: bytes} object.
std::uintmax_t totalBytes(const nlohmann::json& files);

// Renders one camera into a target: how a candidate is drawn.
using DrawFunction = std::function<void(const render::Camera&, const render::RenderTarget&)>;

// Mean-loss PSNR and mean SSIM of `draw` over every held-out view, drawn as the targets were
// (supersampled when they are); view 0's image goes to `quality.view`.
void scoreHoldout(const scene::TargetSet& holdout, const DrawFunction& draw, Quality& quality);
// The same from a score already taken (a fit's own).
void setHoldout(const fit::HoldoutScore& score, Quality& quality);

// A decoded asset.subd in a fitter of its own (the scene's normalised frame), drawn as the fit
// draws; `tessLevel` 0: the fitter's default.
std::unique_ptr<fit::CageFitter> drawnAsFitted(gl::ProgramCache& programs, const fit::FitScene& scene,
                                               const codec::SubdAsset& shipped, int tessLevel = 0);

// Surface distance of `candidate` (triangles, normalised frame) to `reference` (same), reported
// in world units.
geometry::SurfaceDistance worldDistance(const mesh::PolygonMesh& candidate, const mesh::PolygonMesh& reference,
                                        const scene::SceneFrame& frame, int samples);

// The same for a shipped .subd file as a consumer gets it: decoded, displaced, tessellated with
// `segments` per face edge; `frame` is the scene's (the file is in world units).
geometry::SurfaceDistance shippedDistance(const std::filesystem::path& subd, int segments,
                                          const scene::SceneFrame& frame, const mesh::PolygonMesh& reference,
                                          int samples);

}  // namespace subdfit::simplify
