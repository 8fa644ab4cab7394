// subdfit-view: a result shown as it ships (beside its reference and baselines), or the fit of
// `subdfit fit` run step by step in a window while it is shown. Thin: parses options, reads the
// inputs, hands over to the viewer; errors become one line on stderr and exit code 1 (2 for a
// command line that does not parse).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "common/command_line.h"
#include "common/fit_cli.h"
#include "util/error.h"
#include "viewer.h"

namespace {

constexpr const char* kWindowGroup = "Window";
constexpr const char* kResultGroup = "Result view";
constexpr const char* kFitGroup = "Fit (--cage and --reference, or a RESULT with --refine)";
constexpr const char* kFitSettingsGroup = "Fit settings (advanced: docs/viewer.md)";

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "subdfit-view: show a subdfit result beside its reference and baselines, or run a fit live.\n"
        "  subdfit-view RESULT...                     a simplify or fit folder, an asset.subd, .glb files\n"
        "  subdfit-view --cage C --reference R        fit C to R in the window\n"
        "  subdfit-view RESULT --refine               fit a result further"};
    subdfit::view::ViewerOptions options;
    options.fit.out = "out/view";
    std::vector<std::filesystem::path> results;
    bool refine = false;
    app.add_option("RESULT", results,
                   "a fit or simplify output folder, an asset.subd, or mesh files (.glb, .gltf, .obj): "
                   "side by side under one camera");

    std::string mode = "fit";
    std::vector<std::string> modes;
    for (const auto& [key, value] : subdfit::view::viewModesByKey()) modes.push_back(key);
    app.add_option("--mode", mode,
                   "view to start with: fit (shaded), difference (error against the reference), faces, uv, "
                   "displacement, normal, base_color, metallic_roughness; target (the reference) in a fit")
        ->check(CLI::IsMember(modes))
        ->capture_default_str()
        ->group(kWindowGroup);
    app.add_flag("--wireframe", options.cageWireframe,
                 "start with the cage's edges drawn over the view (creases and corners coloured)")
        ->group(kWindowGroup);
    app.add_option("--width", options.width, "window width")
        ->capture_default_str()
        ->check(CLI::Range(320, 8192))
        ->group(kWindowGroup);
    app.add_option("--height", options.height, "window height")
        ->capture_default_str()
        ->check(CLI::Range(240, 8192))
        ->group(kWindowGroup);
    app.add_option("--screenshot", options.screenshot, "write the window as PNG after the last frame, then exit")
        ->group(kWindowGroup);
    app.add_option("--frames", options.frames, "frames to draw before exiting (with --screenshot: default 1)")
        ->check(CLI::PositiveNumber)
        ->group(kWindowGroup);

    std::string layout = "side";
    app.add_option("--layout", layout, "side: every column at once; single: one at a time (left and right keys)")
        ->check(CLI::IsMember({"side", "single"}))
        ->capture_default_str()
        ->group(kResultGroup);
    app.add_option("--show", options.show,
                   "the column shown first one at a time: reference, subdfit, decimation, gltfpack, "
                   "bake, or a file's name (default: subdfit)")
        ->group(kResultGroup);
    app.add_option("--segments", options.tessLevel,
                   "segments per face edge of subdfit-format columns (default: decode's, "
                   "the maps' sample density; a power of two is drawn)")
        ->check(CLI::Range(1, 64))
        ->group(kResultGroup);

    subdfit::view::SubdReading subd;
    app.add_option("--bytes", subd.firstBytes,
                   "read each asset.subd's first N bytes only, as a stream delivers them (as subdfit decode --bytes): "
                   "the cage and the map levels wholly in them, a coarser asset")
        ->check(CLI::Range(std::size_t(1), std::numeric_limits<std::size_t>::max()))
        ->group(kResultGroup);
    app.add_flag("--prefixes", subd.prefixes,
                 "each asset.subd's prefixes as its column's levels (a slider): the whole file (or --bytes), half of "
                 "it, a quarter ... down to its cage alone, each as a download that far draws it")
        ->group(kResultGroup);

    app.add_flag("--refine", refine,
                 "fit the RESULT folder's asset further against its reference (Save writes to --out)")
        ->group(kFitGroup);
    app.add_option("--cage", options.fit.cage, "control cage (.obj with OpenSubdiv tags, .gltf, .glb, .drc)")
        ->group(kFitGroup);
    app.add_option("--reference", options.fit.reference,
                   "reference mesh to match (.obj, .gltf, .glb, .drc); with a RESULT, "
                   "its reference instead of the one report.json names")
        ->group(kFitGroup);
    app.add_option("--out", options.fit.out, "folder the Save button writes to")
        ->capture_default_str()
        ->group(kFitGroup);
    app.add_flag("--paused", options.paused, "start with the fit paused")->group(kFitGroup);
    app.add_flag("--save-on-exit", options.saveOnExit, "save the result into --out (as Save does) when the viewer ends")
        ->group(kFitGroup);
    // The fit's own settings, as `subdfit fit` takes them, in a group of their own.
    subdfit::apps::addFitSettings(app, options.fit);
    for (CLI::Option* option : app.get_options())
        if (option->get_group() == "Options" && option->nonpositional() && option->get_name() != "--help")
            option->group(kFitSettingsGroup);

    if (const auto exitCode = subdfit::apps::parseCommandLine(app, argc, argv, "subdfit-view")) return *exitCode;
    options.mode = subdfit::view::viewModesByKey().at(mode);
    options.sideBySide = layout == "side";
    if (!options.screenshot.empty() && options.frames == 0) options.frames = 1;

    try {
        // --reference with RESULTs (and no --cage) names the result view's reference.
        const bool fitInputs = !options.fit.cage.empty();
        if (results.empty() == !fitInputs || (fitInputs && options.fit.reference.empty()))
            throw subdfit::Error(
                "give a RESULT (a folder, an asset.subd, .glb files) or --cage and --reference (see --help)");
        const std::filesystem::path resultReference = fitInputs ? std::filesystem::path() : options.fit.reference;
        if (refine && results.size() != 1) throw subdfit::Error("invalid option: --refine takes one RESULT folder");
        subdfit::fit::validate(options.fit);
        // The inputs first: a bad file is reported even where no window can be opened.
        if (fitInputs) {
            auto inputs = subdfit::view::loadFitInputs(options.fit);
            subdfit::view::runViewer(options, std::move(inputs));
        } else if (refine) {
            auto inputs = subdfit::view::refineInputs(subdfit::view::loadResultInputs(results, resultReference, subd),
                                                      options.fit);
            subdfit::view::runViewer(options, std::move(inputs));
        } else {
            auto result = subdfit::view::loadResultInputs(results, resultReference, subd);
            subdfit::view::checkResultOptions(options, result);
            subdfit::view::runViewer(options, std::move(result));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "subdfit-view: error: %s\n", subdfit::apps::describeError(e).c_str());
        return 1;
    }
    return 0;
}
