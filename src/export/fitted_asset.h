#pragma once
// The maps a fit produces beside its cage, in the form every exporter reads: node values on the
// shared texel layout (maps/texel_layout.h), before any packing into images.
#include <vector>

#include "maps/texel_layout.h"

namespace subdfit::exporter {

struct FittedMaps {
    maps::TexelLayout layout;
    // layout.nodeCount heights along the limit normal, in the cage's units; empty = no
    // displacement map.
    std::vector<float> displacement;
    // 2 per node: tangent-space (x, y); the normal is normalize(x, y, 1) in the frame
    // (dPdu, dPdv, N) of the limit surface; empty = no normal map.
    std::vector<float> normal;

    bool hasDisplacement() const { return !displacement.empty(); }
    bool hasNormal() const { return !normal.empty(); }
};

}  // namespace subdfit::exporter
