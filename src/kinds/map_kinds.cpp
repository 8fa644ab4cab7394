#include "kinds/map_kinds.h"

namespace subdfit::kinds {

const MapKindInfo* kindWithSection(const std::array<char, 4>& tag) {
    for (const MapKindInfo& i : kMapKinds)
        if (i.section == tag) return &i;
    return nullptr;
}

}  // namespace subdfit::kinds
