#pragma once
// What the 3D view shows. The values are those of glsl/view_modes.h, which the composite
// shader switches on.
#include <array>
#include <map>
#include <string>

#include "maps/map_parameters.h"
#include "view_modes.h"

namespace subdfit::view {

enum class ViewMode {
    Fit = SUBDFIT_VIEW_FIT,                               // the fitted limit surface, shaded as the fit sees it
    Target = SUBDFIT_VIEW_TARGET,                         // the reference, same shading
    Difference = SUBDFIT_VIEW_DIFFERENCE,                 // per-pixel colour error between the two, heat-mapped
    FaceId = SUBDFIT_VIEW_FACE_ID,                        // ptex face id buffer, hashed colours
    Uv = SUBDFIT_VIEW_UV,                                 // patch-local (u, v) buffer
    Displacement = SUBDFIT_VIEW_DISPLACEMENT,             // the surface coloured by its displacement
    NormalMap = SUBDFIT_VIEW_NORMAL_MAP,                  // the surface coloured by its tangent-space normal map
    BaseColor = SUBDFIT_VIEW_BASE_COLOR,                  // its fitted base colour texels, unlit
    MetallicRoughness = SUBDFIT_VIEW_METALLIC_ROUGHNESS,  // its roughness (green) and metallic (blue)
};
constexpr int kViewModeCount = SUBDFIT_VIEW_MODE_COUNT;

const char* viewModeName(ViewMode mode);
// Command-line names: fit, target, difference, faces, uv, displacement, normal, base_color,
// metallic_roughness.
const std::map<std::string, ViewMode>& viewModesByKey();

// The map modes need the scene to have that map.
bool viewModeAvailable(ViewMode mode, maps::MapEffects effects);

// What a mode reads: the fit's buffers, the reference's, or both.
bool viewModeNeedsFit(ViewMode mode);
bool viewModeNeedsTarget(ViewMode mode);

// Colour-map gain of a mode, to start with (the panel adjusts it): difference in colour units,
// displacement in scene units (radius 1), normal-map tangent offsets.
float defaultViewScale(ViewMode mode);
std::array<float, kViewModeCount> defaultViewScales();

}  // namespace subdfit::view
