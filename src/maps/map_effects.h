#pragma once
// Which maps a scene fits: each is a parameter group and a shader variant bit of its own. The
// geometric maps are the user's choice (--maps); the appearance maps follow the scene's shading
// (a base colour wherever there is a material, roughness and metallic under the glTF BRDF).
#include <string>

namespace subdfit::maps {

struct MapEffects {
    bool displacement = false;
    bool normalMap = false;
    bool baseColor = false;          // sRGB base colour, 3 per node
    bool metallicRoughness = false;  // roughness, metallic per node
    bool geometric() const { return displacement || normalMap; }
    bool appearance() const { return baseColor || metallicRoughness; }
    bool any() const { return geometric() || appearance(); }
    friend bool operator==(const MapEffects&, const MapEffects&) = default;
};

// "none", "displacement", "normal", "displacement,normal" (any order). Throws subdfit::Error
// saying what it got.
MapEffects parseMapEffects(const std::string& text);

// The text parseMapEffects reads (of the geometric maps): "none", "displacement", "normal" or
// "displacement,normal".
std::string toString(MapEffects effects);

}  // namespace subdfit::maps
