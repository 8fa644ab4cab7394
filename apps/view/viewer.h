#pragma once
// subdfit-view's main loop: one window, one fit session, a panel; each frame takes a bounded
// slice of fit steps and then draws, so the window answers while the fit runs.
#include <filesystem>

#include "fit_session.h"
#include "view_mode.h"

namespace subdfit::view {

struct ViewerOptions {
    fit::FitOptions fit;
    int width = 1280, height = 800;
    std::filesystem::path screenshot;  // written after the last frame when set
    int frames = 0;                    // > 0: stop after this many frames
    bool paused = false;               // start with the fit paused
    ViewMode mode = ViewMode::Fit;     // the view to start with
    bool cageWireframe = false;
    bool saveOnExit = false;           // write the results into the panel's out folder at the end
    double stepBudgetMs = 16.0;        // fit steps per frame stop once they took this long (at least one runs)
};

// Opens the window and runs until it is closed or `frames` frames are drawn. Throws
// subdfit::Error when no window can be had, the first session cannot be built or `mode` needs
// a map the scene does not have.
void runViewer(const ViewerOptions& options, FitInputs inputs);

}  // namespace subdfit::view
