// subdfit-view: the fit of `subdfit fit`, run step by step in a window while it is shown.
// Thin: parses options, loads the inputs, hands over to the viewer; errors become one line on
// stderr and exit code 1 (2 for a command line that does not parse).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "common/command_line.h"
#include "common/fit_cli.h"
#include "util/error.h"
#include "viewer.h"

int main(int argc, char** argv) {
    CLI::App app{"subdfit-view: run a subdfit fit interactively, showing it live"};
    subdfit::view::ViewerOptions options;
    options.fit.out = "out/view";
    subdfit::apps::addFitOptions(app, options.fit);
    app.add_option("--out", options.fit.out, "folder the Save button writes to")->capture_default_str();
    app.add_option("--width", options.width, "window width")->capture_default_str()->check(CLI::Range(320, 8192));
    app.add_option("--height", options.height, "window height")->capture_default_str()->check(CLI::Range(240, 8192));
    app.add_flag("--paused", options.paused, "start with the fit paused");
    std::string mode = "fit";
    std::vector<std::string> modes;
    for (const auto& [key, value] : subdfit::view::viewModesByKey()) modes.push_back(key);
    app.add_option("--mode", mode, "view to start with: fit, target, difference, faces, uv, displacement, normal, base_color, metallic_roughness")
        ->check(CLI::IsMember(modes))
        ->capture_default_str();
    app.add_flag("--wireframe", options.cageWireframe, "start with the cage's edges drawn over the view");
    app.add_flag("--save-on-exit", options.saveOnExit, "save the result into --out (as Save does) when the viewer ends");
    app.add_option("--screenshot", options.screenshot, "write the window as PNG after the last frame, then exit");
    app.add_option("--frames", options.frames, "frames to draw before exiting (with --screenshot: default 1)")
        ->check(CLI::PositiveNumber);

    if (const auto exitCode = subdfit::apps::parseCommandLine(app, argc, argv, "subdfit-view")) return *exitCode;
    options.mode = subdfit::view::viewModesByKey().at(mode);
    if (!options.screenshot.empty() && options.frames == 0) options.frames = 1;

    try {
        subdfit::fit::validate(options.fit);
        // The inputs first: a bad file is reported even where no window can be opened.
        auto inputs = subdfit::view::loadFitInputs(options.fit);
        subdfit::view::runViewer(options, std::move(inputs));
    } catch (const std::exception& e) {
        std::fprintf(stderr, "subdfit-view: error: %s\n", subdfit::apps::describeError(e).c_str());
        return 1;
    }
    return 0;
}
