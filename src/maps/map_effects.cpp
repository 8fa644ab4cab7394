#include "maps/map_effects.h"

#include <sstream>

#include "util/error.h"

namespace subdfit::maps {

MapEffects parseMapEffects(const std::string& text) {
    MapEffects effects;
    if (text == "none" || text.empty()) return effects;
    std::istringstream items(text);
    for (std::string item; std::getline(items, item, ',');) {
        if (item == "displacement") effects.displacement = true;
        else if (item == "normal") effects.normalMap = true;
        else throw Error("takes none, displacement, normal or displacement,normal; got '" + text + "'");
    }
    return effects;
}

std::string toString(MapEffects effects) {
    if (effects.displacement && effects.normalMap) return "displacement,normal";
    if (effects.displacement) return "displacement";
    if (effects.normalMap) return "normal";
    return "none";
}

}  // namespace subdfit::maps
