#pragma once
// Which maps a scene fits: each is a parameter group and a shader variant bit of its own.
#include <string>

namespace subdfit::maps {

struct MapEffects {
    bool displacement = false;
    bool normalMap = false;
    bool any() const { return displacement || normalMap; }
    friend bool operator==(const MapEffects&, const MapEffects&) = default;
};

// "none", "displacement", "normal", "displacement,normal" (any order). Throws subdfit::Error
// saying what it got.
MapEffects parseMapEffects(const std::string& text);

// The text parseMapEffects reads: "none", "displacement", "normal" or "displacement,normal".
std::string toString(MapEffects effects);

}  // namespace subdfit::maps
