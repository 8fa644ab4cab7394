#pragma once
// subdfit-view's main loop: one window and a panel, showing either a result (the shipped asset
// beside its reference and baselines) or a fit session (each frame takes a bounded slice of fit
// steps and then draws, so the window answers while the fit runs). A result can be refined:
// the window then runs a fit that starts from it.
#include <filesystem>
#include <string>

#include "fit_session.h"
#include "result_scene.h"
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
    bool saveOnExit = false;     // write the results into the panel's out folder at the end
    double stepBudgetMs = 16.0;  // fit steps per frame stop once they took this long (at least one runs)
    // The result view's:
    bool sideBySide = true;  // every column at once, else one at a time
    std::string show;        // the column shown first one at a time ("" : subdfit's, else the first)
    int tessLevel = 0;       // segments per face edge of subdfit-format columns; 0: decode's default
};

// Opens the window and runs the fit of `inputs` until it is closed or `frames` frames are drawn.
// Throws subdfit::Error when no window can be had, the session cannot be built or `mode` needs
// a map the scene does not have.
void runViewer(const ViewerOptions& options, FitInputs inputs);

// The same for a result (loadResultInputs); options.fit is what a refinement starts from.
void runViewer(const ViewerOptions& options, ResultInputs result);

// Throws subdfit::Error when `mode` cannot show this result, or options.show names no column.
void checkResultOptions(const ViewerOptions& options, const ResultInputs& result);

}  // namespace subdfit::view
