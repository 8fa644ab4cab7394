// subdfit-bench: benchmark drivers that print figures and write CSV. Timings are ratios
// measured within one run; absolute times only mean something on a dedicated GPU.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <tuple>
#include <utility>
#include <vector>

#include "common/command_line.h"
#include "common/fit_cli.h"
#include "bench_commands.h"
#include "io/output_folder.h"
#include "util/error.h"

int main(int argc, char** argv) {
    CLI::App app{"subdfit-bench: what accuracy costs in time"};
    app.require_subcommand(1);

    // Each subcommand runs its options struct; addOut registers its --out with the CSV that marks
    // the folder as the command's own, so the folder is checked before minutes of benchmarking
    // (a typo or somebody's files need --force; the command's CSV from an earlier run it updates).
    std::vector<std::pair<CLI::App*, std::function<int()>>> runs;
    std::vector<std::tuple<CLI::App*, const std::filesystem::path*, const char*>> outputs;
    const auto command = [&]<class Options>(const char* name, const char* what, Options& options,
                                            int (*run)(const Options&)) {
        CLI::App* subcommand = app.add_subcommand(name, what);
        runs.emplace_back(subcommand, [&options, run] { return run(options); });
        return subcommand;
    };
    const auto addOut = [&](CLI::App* subcommand, std::filesystem::path& out, const char* csv, const char* help) {
        outputs.emplace_back(subcommand, &out, csv);
        return subcommand->add_option("--out", out, help);
    };

    subdfit::bench::StepCostOptions stepCost;
    auto* stepCostCommand =
        command("step-cost", "SGE step time / forward render time, and scaling", stepCost, subdfit::bench::runStepCost);
    addOut(stepCostCommand, stepCost.out, "step_cost.csv", "folder for step_cost.csv");
    stepCostCommand
        ->add_option("--repeats", stepCost.repeats, "interleaved rounds (forward render, step, step in halves)")
        ->capture_default_str();
    stepCostCommand->add_option("--res", stepCost.resolutions, "resolutions timed")->capture_default_str();
    stepCostCommand->add_flag("!--no-scaling", stepCost.scaling, "skip the table against parameter count");
    subdfit::apps::addGlProvider(*stepCostCommand, stepCost.glProvider);

    subdfit::bench::LumpySphereOptions lumpy;
    auto* lumpyCommand = command("lumpy-sphere", "fit a quad-sphere cage to a lumpy sphere (the peer's task)", lumpy,
                                 subdfit::bench::runLumpySphere);
    addOut(lumpyCommand, lumpy.out, "lumpy_sphere.csv", "output folder")->capture_default_str();
    lumpyCommand->add_option("--steps", lumpy.steps, "most optimisation steps (default: the device's)");
    lumpyCommand->add_option("--noise-gate", lumpy.noiseGate, "the fit's noise gate (0: plain Adam)")
        ->capture_default_str();
    lumpyCommand->add_option("--res", lumpy.resolution, "resolution")->capture_default_str();
    lumpyCommand->add_option("--views", lumpy.views, "training views")->capture_default_str();
    lumpyCommand->add_option("--bumps", lumpy.bumps, "bumps of the lumpy sphere")->capture_default_str();
    lumpyCommand->add_option("--amplitude", lumpy.amplitude, "their height (sphere radius 1)")->capture_default_str();
    lumpyCommand->add_option("--lumps-seed", lumpy.lumpsSeed, "the seed placing them")->capture_default_str();
    lumpyCommand->add_option("--cage-divisions", lumpy.cageDivisions, "the sphere cage's quads per cube-face edge")
        ->capture_default_str()
        ->check(CLI::Range(2, 32));
    lumpyCommand->add_option("--seed", lumpy.seed, "the fit's seed (views, perturbations)")->capture_default_str();
    subdfit::apps::addGlProvider(*lumpyCommand, lumpy.glProvider);

    subdfit::bench::SimplifyTradeoffOptions tradeoff;
    auto* simplifyCommand = command(
        "simplify",
        "simplify at byte budgets: PSNR and mean surface distance against bytes, vs the baselines; seconds by stage",
        tradeoff, subdfit::bench::runSimplifyTradeoff);
    addOut(simplifyCommand, tradeoff.out, "simplify_tradeoff.csv", "output folder")->capture_default_str();
    simplifyCommand->add_option("--reference", tradeoff.references, "dense assets (default: the relief Spot)");
    simplifyCommand->add_option("--budgets", tradeoff.budgets, "byte budgets")->capture_default_str();
    simplifyCommand->add_option("--steps", tradeoff.steps, "optimisation steps per run (default: the device's)");
    simplifyCommand->add_option("--res", tradeoff.resolution, "render resolution (default: the device's)");
    subdfit::apps::addNamedOption(*simplifyCommand, "--compare", tradeoff.compare,
                                  "what each run compares: none, fast or full");
    subdfit::apps::addNamedOption(*simplifyCommand, "--cage-shape", tradeoff.cageShape,
                                  "the cages' faces: auto, triangles, quads or paired (as simplify's)");
    subdfit::apps::addGlProvider(*simplifyCommand, tradeoff.glProvider);

    subdfit::bench::ConvergenceOptions convergence;
    auto* convergenceCommand =
        command("convergence", "a sphere cage 30 % small fitted to a lumpy sphere: Chamfer against time", convergence,
                subdfit::bench::runConvergence);
    addOut(convergenceCommand, convergence.out, "convergence.csv", "output folder")->capture_default_str();
    convergenceCommand->add_option("--start-scale", convergence.startScale, "the cage's size against the reference's")
        ->capture_default_str();
    convergenceCommand->add_option("--every", convergence.every, "steps between Chamfer measurements")
        ->capture_default_str();
    convergenceCommand->add_option("--bumps", convergence.bumps, "bumps of the lumpy sphere")->capture_default_str();
    convergenceCommand->add_option("--amplitude", convergence.amplitude, "their height (sphere radius 1)")
        ->capture_default_str();
    convergenceCommand->add_option("--lumps-seed", convergence.seed, "the seed placing them")->capture_default_str();
    subdfit::apps::addFitSettings(*convergenceCommand, convergence.fit);

    subdfit::bench::RecoveryOptions recovery;
    auto* recoveryCommand =
        command("recovery", "noised (creased) cages fitted back to their own limit surface (8 views unless --views)",
                recovery, subdfit::bench::runRecovery);
    addOut(recoveryCommand, recovery.out, "recovery.csv", "output folder")->capture_default_str();
    recoveryCommand->add_option("--shapes", recovery.shapes, "cages (OBJ with OpenSubdiv tags)")->capture_default_str();
    recoveryCommand->add_option("--sigma", recovery.sigma, "noise, a fraction of the scene radius")
        ->capture_default_str();
    subdfit::apps::addFitSettings(*recoveryCommand, recovery.fit);

    subdfit::bench::MapsGainOptions mapsGain;
    auto* mapsCommand =
        command("maps", "held-out PSNR, time and bytes with and without maps", mapsGain, subdfit::bench::runMapsGain);
    addOut(mapsCommand, mapsGain.out, "maps_gain.csv", "output folder")->capture_default_str();
    mapsCommand->add_option("--cage", mapsGain.cage, "the cage (default: the ~200-quad sphere cage)");
    mapsCommand->add_option(
        "--reference", mapsGain.reference,
        "the reference (default: with --cage, its limit surface with a relief; else a bumpy sphere)");
    mapsCommand
        ->add_option("--relief-amplitude", mapsGain.reliefAmplitude,
                     "with --cage alone: the relief's RMS height, a fraction of the bounding-box diagonal")
        ->capture_default_str();
    mapsCommand->add_option("--relief-seed", mapsGain.reliefSeed, "with --cage alone: the seed of the relief's waves")
        ->capture_default_str();
    mapsCommand->add_option("--compare", mapsGain.compared, "maps each compared with a vertex-only fit")
        ->capture_default_str();
    subdfit::apps::addFitSettings(*mapsCommand, mapsGain.fit);

    subdfit::bench::FitGainOptions fitGain;
    auto* fitGainCommand = command("fit-gain",
                                   "a fit from a good start (a limit-fitted cage, baked maps): held-out dB gain "
                                   "against seconds, variant by variant",
                                   fitGain, subdfit::bench::runFitGain);
    addOut(fitGainCommand, fitGain.out, "fit_gain.csv", "output folder")->capture_default_str();
    fitGainCommand->add_option("--cage", fitGain.cage, "the starting cage (world units)");
    fitGainCommand->add_option("--faces", fitGain.faces,
                               "start from simplify's initial cage of about this many faces instead");
    fitGainCommand->add_option("--reference", fitGain.reference, "the dense reference")->required();
    fitGainCommand->add_option(
        "--variant", fitGain.variants,
        "fit options over the common ones, \"key=value;key=value\" (report.json's keys); one run each");
    fitGainCommand->add_option("--every", fitGain.every, "steps per turn")->capture_default_str();
    subdfit::apps::addFitSettings(*fitGainCommand, fitGain.fit);

    subdfit::bench::AccuracyOptions accuracy;
    auto* accuracyCommand = command("accuracy", "held-out PSNR and Chamfer against wall time, knob by knob", accuracy,
                                    subdfit::bench::runAccuracy);
    addOut(accuracyCommand, accuracy.out, "accuracy.csv", "output folder")->capture_default_str();
    accuracyCommand->add_option("--steps", accuracy.baseSteps, "base step count")->capture_default_str();
    subdfit::apps::addGlProvider(*accuracyCommand, accuracy.glProvider);

    subdfit::bench::ReliefOptions relief;
    auto* reliefCommand =
        command("relief", "write a dense reference: a cage's limit surface with fine procedural relief", relief,
                subdfit::bench::runRelief);
    reliefCommand->add_option("--cage", relief.cage, "cage whose limit surface is the base")->capture_default_str();
    reliefCommand->add_option("--out", relief.out, "the .glb to write")->capture_default_str();
    reliefCommand->add_option("--mesh", relief.mesh,
                              "a textured triangle asset (.gltf, .glb, .obj) to split and relieve instead");
    reliefCommand->add_option("--splits", relief.splits, "with --mesh: 4-splits of its triangles")
        ->capture_default_str()
        ->check(CLI::Range(0, 5));
    reliefCommand->add_option("--segments", relief.relief.segments, "tessellation per ptex-face edge")
        ->capture_default_str();
    reliefCommand
        ->add_option("--amplitude", relief.relief.amplitude, "RMS height, a fraction of the bounding-box diagonal")
        ->capture_default_str();
    reliefCommand->add_option("--seed", relief.relief.seed, "seed of the relief's waves")->capture_default_str();
    reliefCommand
        ->add_option("--coverage", relief.relief.coverage,
                     "the share of the surface the relief covers, in patches (1: everywhere), the rest left smooth")
        ->check(CLI::Range(0.0f, 1.0f))
        ->capture_default_str();

    subdfit::bench::GradientOptions gradient;
    auto* gradientCommand = command("gradient", "SGE gradient quality against cost; per-pixel vs full-image; ε",
                                    gradient, subdfit::bench::runGradientQuality);
    addOut(gradientCommand, gradient.out, "gradient.csv", "output folder")->capture_default_str();
    gradientCommand->add_option("--samples", gradient.maxSamples, "largest k")->capture_default_str();
    subdfit::apps::addGlProvider(*gradientCommand, gradient.glProvider);

    subdfit::bench::SoupOptions soup;
    auto* soupCommand = command("soup", "triangle soup fitted to an image: per-pixel vs full-image SGE (Fig. 2)", soup,
                                subdfit::bench::runSoup);
    addOut(soupCommand, soup.out, "soup.csv", "output folder")->capture_default_str();
    soupCommand->add_option("--triangles", soup.triangles, "triangles (12 parameters each)")->capture_default_str();
    soupCommand->add_option("--steps", soup.steps, "optimisation steps per estimator")->capture_default_str();
    soupCommand->add_option("--res", soup.resolution, "resolution")->capture_default_str();
    soupCommand->add_option("--seconds", soup.seconds, "step-time budget per estimator (0: none)")
        ->capture_default_str();
    subdfit::apps::addGlProvider(*soupCommand, soup.glProvider);

    subdfit::bench::DecodeLodsOptions decodeLods;
    auto* lodsCommand =
        command("lods", "decode --lods: each level's bytes and distances next to gltfpack's at its triangles",
                decodeLods, subdfit::bench::runDecodeLods);
    lodsCommand->add_option("asset", decodeLods.asset, "an asset.subd")->required();
    lodsCommand->add_option("--reference", decodeLods.reference,
                            "its dense reference, for gltfpack's levels of it and distances to it");
    lodsCommand->add_option("--lods", decodeLods.lods, "levels")->capture_default_str()->check(CLI::Range(2, 8));
    addOut(lodsCommand, decodeLods.out, "decode_lods.csv", "output folder")->capture_default_str();

    subdfit::bench::SubdPrefixOptions prefix;
    auto* prefixCommand =
        command("prefix", "asset.subd prefixes as a stream delivers them: held-out PSNR against bytes", prefix,
                subdfit::bench::runSubdPrefix);
    prefixCommand->add_option("asset", prefix.asset, "the asset.subd to cut")->required();
    prefixCommand->add_option("made", prefix.made, "files made for their own budgets, scored whole beside it");
    prefixCommand->add_option("--reference", prefix.reference, "the dense reference they were made from")->required();
    prefixCommand->add_option("--cuts", prefix.cuts, "prefixes between the cage's end and the file's end")
        ->capture_default_str()
        ->check(CLI::Range(1, 256));
    prefixCommand
        ->add_option_function<std::vector<int>>(
            "--grow",
            [&prefix](const std::vector<int>& grow) {
                prefix.growResolution = grow[0];
                prefix.growBits = grow[1];
            },
            "T,BITS: cut a file grown from the asset instead: its cage with heights baked at T cells a face edge and "
            "BITS, its own lattice first")
        ->expected(2)
        ->delimiter(',')
        ->check(CLI::Range(1, 64));
    prefixCommand
        ->add_option("--prefix-bits", prefix.prefixBits,
                     "the asset's bits: the grown heights' step is its step over 2^(BITS - these)")
        ->capture_default_str()
        ->check(CLI::Range(1, 24));
    subdfit::apps::addGlProvider(*prefixCommand, prefix.glProvider);
    addOut(prefixCommand, prefix.out, "subd_prefix.csv", "output folder")->capture_default_str();

    bool force = false;
    app.add_flag("--force", force, "write into a non-empty --out folder that holds no earlier results of the command");

    if (const auto exitCode = subdfit::apps::parseCommandLine(app, argc, argv, "subdfit-bench")) return *exitCode;
    try {
        for (const auto& [subcommand, out, csv] : outputs)
            if (subcommand->parsed() && !out->empty())
                subdfit::io::checkOutputFolder(*out, {.ownMarkers = {csv}, .force = force});
        for (const auto& [subcommand, run] : runs)
            if (subcommand->parsed()) return run();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "subdfit-bench: error: %s\n", subdfit::apps::describeError(e).c_str());
        return 1;
    }
    return 0;
}
