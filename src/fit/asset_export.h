#pragma once
// What a fit ships besides cage.obj: asset.subd, the cage and maps in one compact file
// (export/subd_format.h, the maps at --map-bits) that `subdfit decode` turns into triangles;
// displacement.exr, normal.png and maps.json when the scene has maps (for DCC tools); and with
// --preview fitted.glb -- the cage's limit surface tessellated as rendered, displaced, with the
// normal map, in world units (--draco: Draco-compressed).
#include <nlohmann/json.hpp>

#include "fit/cage_fitter.h"
#include "fit/fit_options.h"
#include "scene/scene_frame.h"

namespace subdfit::fit {

// Returns {file name: bytes} of everything written (each file atomically).
nlohmann::json exportAsset(const FitOptions& options, CageFitter& fitter, const scene::SceneFrame& frame,
                           const mesh::PolygonMesh& fittedWorld);

}  // namespace subdfit::fit
