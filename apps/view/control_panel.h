#pragma once
// The viewer's ImGui side panel: fit controls, per-group knobs, view mode, loss curve, save
// and load. Knobs that only set a value act on the session directly; anything that rebuilds
// or replaces objects comes back as a request for the viewer to carry out between frames.
#include <array>
#include <string>

#include "fit_session.h"
#include "view_renderer.h"

namespace subdfit::view {

// What the panel edits, kept across frames.
struct PanelState {
    bool playing = true;
    ViewSettings view;
    std::array<float, kViewModeCount> scales = defaultViewScales();  // per mode, so switching back keeps a gain
    int tessLevel = 8;
    std::string outPath, cagePath, referencePath;
    std::string status;  // the last save or load, or an error (shown in red)
    bool statusIsError = false;
    float stepsPerSecond = 0.0f;
};

struct PanelRequests {
    bool step = false, save = false, load = false, applyTessLevel = false, resetCamera = false;
};

// A window pinned to the left edge, `width` wide, the window's full height.
PanelRequests drawControlPanel(PanelState& state, FitSession& session, float width, float height);

}  // namespace subdfit::view
