#pragma once
// The result view's ImGui side panel: the columns with their bytes and held-out scores, which
// are shown and how (side by side, or one at a time), the view mode, the cage wireframe and its
// legend, the tessellation and the level of detail. Anything that rebuilds objects comes back
// as a request for the viewer to carry out between frames.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "result_scene.h"
#include "view_renderer.h"

namespace subdfit::view {

struct ResultPanelState {
    bool sideBySide = true;
    int shown = 0;              // the column shown one at a time
    std::vector<char> visible;  // per column, side by side
    ViewSettings view;
    std::array<float, kViewModeCount> scales = defaultViewScales();
    int tessLevel = 8;       // the slider; applied on request
    bool canRefine = false;  // a folder whose reference is there
    std::string status;
    bool statusIsError = false;
};

struct ResultPanelRequests {
    bool applyTessLevel = false, resetCamera = false, refine = false;
    int levelColumn = -1, level = 0;  // a column's level of detail changed
};

// The modes the result view offers, given the columns' maps and whether a reference is shown.
bool resultModeAvailable(ViewMode mode, maps::MapEffects anyColumn, bool reference);

ResultPanelRequests drawResultPanel(ResultPanelState& state, const ResultInputs& inputs,
                                    std::vector<std::unique_ptr<ResultColumn>>& columns, float width, float height);

}  // namespace subdfit::view
