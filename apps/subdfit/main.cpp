// subdfit: the batch command line. Thin: parses options, forwards to the core, turns errors into
// one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "fit/fit_job.h"
#include "util/error.h"

namespace {

std::atomic<bool> interrupted{false};

void onInterrupt(int) { interrupted = true; }

void printProgress(const subdfit::fit::Progress& p) {
    std::fprintf(stderr, "step %d/%d  loss %.4e  %.1f s  ETA %.0f s\n", p.step, p.steps, double(p.loss),
                 p.seconds, p.etaSeconds);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"subdfit: fit Catmull-Clark cages (and maps) to renders of a reference"};
    app.require_subcommand(1);

    subdfit::fit::FitOptions fit;
    auto* fitCommand = app.add_subcommand("fit", "fit the control vertices of a cage to a reference mesh");
    fitCommand->add_option("--cage", fit.cage, "control cage (.obj with OpenSubdiv tags, .gltf, .glb, .drc)")->required();
    fitCommand->add_option("--reference", fit.reference, "reference mesh to match (.obj, .gltf, .glb, .drc)")->required();
    fitCommand->add_option("--out", fit.out, "output folder")->required();
    fitCommand->add_option("--views", fit.views, "training views on a sphere")->capture_default_str();
    fitCommand->add_option("--holdout-views", fit.holdoutViews, "held-out evaluation views")->capture_default_str();
    fitCommand->add_option("--res", fit.resolution, "render resolution in pixels")->capture_default_str();
    fitCommand->add_option("--steps", fit.steps, "optimisation steps")->capture_default_str();
    fitCommand->add_option("--seed", fit.seed, "random seed (views, perturbations)")->capture_default_str();
    fitCommand->add_option("--views-per-step", fit.viewsPerStep, "views rendered per step")->capture_default_str();
    fitCommand->add_option("--samples-per-step", fit.samplesPerStep, "perturbations averaged per step")->capture_default_str();
    fitCommand->add_option("--tess", fit.tessLevel, "tessellation segments per face edge")->capture_default_str();
    fitCommand->add_option("--epsilon", fit.epsilon, "vertex perturbation (scene radius = 1)")->capture_default_str();
    fitCommand->add_option("--lr", fit.learningRate, "vertex learning rate (scene radius = 1)")->capture_default_str();
    fitCommand->add_option("--smoothing", fit.smoothing, "Laplacian preconditioner strength (0 = off)")->capture_default_str();
    fitCommand->add_option("--maps", fit.maps, "maps to fit: none, displacement, normal, displacement,normal")->capture_default_str();
    fitCommand->add_option("--map-res", fit.mapResolution, "map cells per face edge")->capture_default_str();
    fitCommand->add_option("--maps-start", fit.mapsStart, "fraction of the steps before the maps join")->capture_default_str();
    fitCommand->add_flag("--draco", fit.draco, "write fitted.glb with Draco compression");
    fitCommand->add_flag("--resume", fit.resume, "continue from DIR/checkpoint.bin (same inputs and settings)");
    fitCommand->add_option("--checkpoint-every", fit.checkpointEvery, "steps between checkpoints")->capture_default_str();
    fitCommand->add_option("--gl", fit.glProvider, "GL provider: auto, osmesa, egl")->capture_default_str();

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        if (e.get_exit_code() == 0) return app.exit(e);  // --help
        std::fprintf(stderr, "%s: error: %s (see --help)\n", "subdfit", e.what());
        return 2;
    }

    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
    try {
        if (fitCommand->parsed()) {
            const auto report = subdfit::fit::runFit(fit, {.progress = printProgress, .cancel = &interrupted});
            std::fprintf(stderr, "done: %d steps in %.1f s, loss %.4e -> %.4e, held-out PSNR %.2f -> %.2f dB\n",
                         report["steps"].get<int>(), report["seconds"].get<double>(),
                         report["loss_initial"].get<double>(), report["loss_final"].get<double>(),
                         report["psnr_holdout_initial"].get<double>(), report["psnr_holdout"].get<double>());
            std::cout << (fit.out / "report.json").string() << "\n";
        }
    } catch (const subdfit::Error& e) {
        std::fprintf(stderr, "subdfit: error: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "subdfit: error: %s\n", e.what());
        return 1;
    }
    return interrupted ? 130 : 0;
}
