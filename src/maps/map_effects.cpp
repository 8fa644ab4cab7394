#include "maps/map_effects.h"

#include <sstream>

#include "util/error.h"

namespace subdfit::maps {

MapEffects appearanceFor(render::ShadingModel shading) {
    MapEffects effects;
    effects.set(MapKind::BaseColor, shading != render::ShadingModel::Geometry);
    effects.set(MapKind::MetallicRoughness, shading == render::ShadingModel::MetallicRoughness);
    return effects;
}

MapEffects parseMapEffects(const std::string& text) {
    MapEffects effects;
    if (text == "none" || text.empty()) return effects;
    std::istringstream items(text);
    for (std::string item; std::getline(items, item, ',');) {
        const kinds::MapKindInfo* named = nullptr;
        for (const kinds::MapKindInfo& i : kinds::kMapKinds)
            if (!i.word.empty() && i.word == item) named = &i;
        if (!named) throw Error("takes none, displacement, normal or displacement,normal; got '" + text + "'");
        effects.set(named->kind);
    }
    return effects;
}

std::string toString(MapEffects effects) {
    std::string out;
    for (const kinds::MapKindInfo& i : kinds::kMapKinds)
        if (!i.word.empty() && effects.has(i.kind)) out += (out.empty() ? "" : ",") + std::string(i.word);
    return out.empty() ? "none" : out;
}

}  // namespace subdfit::maps
