#pragma once
// What a fit ships besides cage.obj: asset.subd, the cage and maps in one compact file
// (codec/subd_format.h, the maps at --map-bits) that `subdfit decode` turns into triangles;
// displacement.exr, normal.png and maps.json when the scene has maps (for DCC tools); and with
// --preview fitted.glb -- the cage's limit surface tessellated as rendered, displaced, with the
// normal map, in world units (--draco: Draco-compressed); asset.usdz (--usd), what asset.subd
// holds as a USD package that DCC tools and renderers open (export/usd/usd_export.h).
#include <cstdint>

#include <nlohmann/json.hpp>

#include "codec/subd_format.h"
#include "fit/cage_fitter.h"
#include "fit/fit_options.h"
#include "scene/scene_frame.h"

namespace subdfit::fit {

// How asset.subd codes what `options` asks: --map-bits, the appearance's JPEG quality, the
// cage's position bits.
codec::SubdPrecision subdPrecision(const FitOptions& options);

// What asset.subd codes of `fitter`'s state, before coding: the cage as fitted (`fittedWorld`,
// world units) and the maps on it, heights in world units, laid out on the cage as it decodes at
// options.positionBits.
codec::SubdAsset shippableState(const FitOptions& options, CageFitter& fitter, const scene::SceneFrame& frame,
                                const mesh::PolygonMesh& fittedWorld, std::uint32_t referenceTriangles);

// Returns {file name: bytes} of everything written (each file atomically). asset.subd records
// `referenceTriangles` as what it decodes to by default.
nlohmann::json exportAsset(const FitOptions& options, CageFitter& fitter, const scene::SceneFrame& frame,
                           const mesh::PolygonMesh& fittedWorld, std::uint32_t referenceTriangles);

// asset.usdz (and asset.usda) of dir/asset.subd as it ships, as options.usd asks, the units those
// of options.reference's format. Whoever rewrites asset.subd calls it again. Returns {file name: bytes}.
nlohmann::json exportUsd(const FitOptions& options, const std::filesystem::path& dir);

}  // namespace subdfit::fit
