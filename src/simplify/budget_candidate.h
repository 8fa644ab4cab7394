#pragma once
// One asset the budget search tries (simplify/budget_search.h): a cage with maps, appearance and
// bits, its bytes as shipped and its loss as drawn. Its own header, so that the search and the
// choice among its candidates (simplify/candidate_choice.h) each include it, not each other.
#include <cstdint>

#include "maps/map_effects.h"
#include "surface/surface_maps.h"

namespace subdfit::simplify {

struct BudgetCandidate {
    int faces = 0;          // of the cage, as built
    int quads = 0;          // of those faces
    maps::MapEffects maps;  // none: the bare cage
    int mapResolution = 0;  // 0 without maps
    int mapBits = 0;        // per map value in asset.subd; 0 without maps
    int positionBits = 14;  // per cage coordinate in asset.subd
    // With heights, what shades them: whichever of the two scored lower on the monitor views
    // (over budget, not judged: Displaced).
    surface::ShadingNormal shadingNormal = surface::ShadingNormal::Displaced;
    int appearanceResolution = 0;  // of the base colour (and metallic-roughness); 0 without
    int appearanceQuality = 0;     // JPEG quality of the appearance images; 0 without
    int appearanceAtlas = 0;       // texels per side of the appearance in the reference's atlas; 0: tiles
    std::uintmax_t bytes = 0;      // of its asset.subd
    double monitorLoss = 0.0;      // of the decoded asset; 0 when over budget (not rendered)
    // Over the monitor views and `settledViews` training views, for those near the lowest monitor
    // loss; 0 otherwise.
    double settledLoss = 0.0;
    int settledViews = 0;

    bool quadDominant() const { return 2 * quads > faces; }
};

}  // namespace subdfit::simplify
