// subdfit: the batch command line. Thin: parses options, forwards to the core, turns errors into
// one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <iostream>

#include "fit/fit_job.h"
#include "simplify/simplify_job.h"
#include "util/error.h"

namespace {

std::atomic<bool> interrupted{false};

void onInterrupt(int) { interrupted = true; }

void printSummary(const nlohmann::json& report) {
    std::fprintf(stderr, "done: %d steps in %.1f s, loss %.4e -> %.4e, held-out PSNR %.2f -> %.2f dB\n",
                 report["steps"].get<int>(), report["seconds"].get<double>(), report["loss_initial"].get<double>(),
                 report["loss_final"].get<double>(), report["psnr_holdout_initial"].get<double>(),
                 report["psnr_holdout"].get<double>());
}

void printComparison(const nlohmann::json& report) {
    std::fprintf(stderr, "%-11s %10s %12s %12s\n", "", "bytes", "PSNR (dB)", "Chamfer");
    auto row = [](const char* name, const nlohmann::json& q, double psnr) {
        std::fprintf(stderr, "%-11s %10llu %12.2f %12.4e\n", name, (unsigned long long)q["bytes"].get<std::uint64_t>(),
                     psnr, q["chamfer"].get<double>());
    };
    row("subdfit", report, report["psnr_holdout"].get<double>());
    for (const char* name : {"decimation", "bake"}) {
        const auto& b = report["baselines"][name];
        row(name, b, b["psnr_holdout"].get<double>());
    }
}

void printProgress(const subdfit::fit::Progress& p) {
    std::fprintf(stderr, "step %d/%d  loss %.4e  %.1f s  ETA %.0f s\n", p.step, p.steps, double(p.loss),
                 p.seconds, p.etaSeconds);
}

// The settings `fit` and `simplify` share: everything but the inputs and the output folder.
void addFitSettings(CLI::App& command, subdfit::fit::FitOptions& fit) {
    command.add_option("--views", fit.views, "training views on a sphere")->capture_default_str();
    command.add_option("--holdout-views", fit.holdoutViews, "held-out evaluation views")->capture_default_str();
    command.add_option("--res", fit.resolution, "render resolution in pixels")->capture_default_str();
    command.add_option("--steps", fit.steps, "optimisation steps")->capture_default_str();
    command.add_option("--seed", fit.seed, "random seed (views, perturbations)")->capture_default_str();
    command.add_option("--views-per-step", fit.viewsPerStep, "views rendered per step")->capture_default_str();
    command.add_option("--samples-per-step", fit.samplesPerStep, "perturbations averaged per step")->capture_default_str();
    command.add_option("--tess", fit.tessLevel, "tessellation segments per face edge")->capture_default_str();
    command.add_option("--epsilon", fit.epsilon, "vertex perturbation (scene radius = 1)")->capture_default_str();
    command.add_option("--lr", fit.learningRate, "vertex learning rate (scene radius = 1)")->capture_default_str();
    command.add_option("--smoothing", fit.smoothing, "Laplacian preconditioner strength (0 = off)")->capture_default_str();
    command.add_option("--maps", fit.maps, "maps to fit: none, displacement, normal, displacement,normal")->capture_default_str();
    command.add_option("--map-res", fit.mapResolution, "map cells per face edge")->capture_default_str();
    command.add_option("--maps-start", fit.mapsStart, "fraction of the steps before the maps join")->capture_default_str();
    command.add_flag("--draco", fit.draco, "compress the exported meshes with Draco");
    command.add_flag("--resume", fit.resume, "continue from DIR/checkpoint.bin (same inputs and settings)");
    command.add_option("--checkpoint-every", fit.checkpointEvery, "steps between checkpoints")->capture_default_str();
    command.add_option("--gl", fit.glProvider, "GL provider: auto, osmesa, egl")->capture_default_str();
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
    addFitSettings(*fitCommand, fit);

    subdfit::simplify::SimplifyOptions simplify;
    simplify.fit.maps = "displacement,normal";
    simplify.fit.mapResolution = 4;
    auto* simplifyCommand = app.add_subcommand("simplify", "simplify a dense asset into a light cage and maps, with a quality report");
    simplifyCommand->add_option("reference", simplify.fit.reference, "dense reference asset (.obj, .gltf, .glb, .drc)")->required();
    simplifyCommand->add_option("--faces", simplify.faces, "triangles of the cage")->capture_default_str();
    simplifyCommand->add_option("--out", simplify.fit.out, "output folder")->required();
    addFitSettings(*simplifyCommand, simplify.fit);

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
        const subdfit::fit::FitHooks hooks{.progress = printProgress, .cancel = &interrupted};
        if (fitCommand->parsed()) {
            const auto report = subdfit::fit::runFit(fit, hooks);
            printSummary(report);
            std::cout << (fit.out / "report.json").string() << "\n";
        }
        if (simplifyCommand->parsed()) {
            const auto report = subdfit::simplify::runSimplify(simplify, hooks);
            printSummary(report);
            printComparison(report);
            std::cout << (simplify.fit.out / "report.json").string() << "\n";
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
