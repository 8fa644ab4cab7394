#pragma once
// Which maps a scene fits: each is a parameter group and a shader variant bit of its own. The
// geometric maps are the user's choice (--maps); the appearance maps follow the scene's shading
// (a base colour wherever there is a material, roughness and metallic under the glTF BRDF).
#include <string>

#include "kinds/map_kinds.h"
#include "render/shading_model.h"

namespace subdfit::maps {

using kinds::MapKind;
using MapEffects = kinds::MapKinds;

// The appearance maps a shading model calls for: a base colour wherever there is a material,
// roughness and metallic under the glTF BRDF.
MapEffects appearanceFor(render::ShadingModel shading);

// "none" or geometric kinds' --maps words joined by commas, in any order ("displacement",
// "normal", "displacement,normal"). Throws subdfit::Error saying what it got.
MapEffects parseMapEffects(const std::string& text);

// The text parseMapEffects reads (of the geometric maps), in table order: "none",
// "displacement", "normal" or "displacement,normal".
std::string toString(MapEffects effects);

}  // namespace subdfit::maps
