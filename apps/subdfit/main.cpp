// subdfit: the batch command line. Thin: parses options, forwards to the core, turns errors into
// one line on stderr and a non-zero exit.
#include <CLI/CLI.hpp>

#include <atomic>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>

#include "common/command_line.h"
#include "common/simplify_cli.h"
#include "common/error_bound.h"
#include "export/engine/engine_decode.h"
#include "fit/fit_job.h"
#include "manifest.h"
#include "simplify/simplify_job.h"
#include "util/error.h"
#include "util/interrupt.h"
#include "util/printable.h"

namespace {

void printSummary(const subdfit::fit::FitReport& r) {
    std::fprintf(stderr, "done: %d steps in %.1f s", r.steps, r.seconds);
    if (r.trainBefore && r.trainAfter)
        std::fprintf(stderr, ", loss %.4e -> %.4e", r.trainBefore->loss, r.trainAfter->loss);
    std::fprintf(stderr, ", held-out PSNR as fitted (before coding) %.2f -> %.2f dB\n", r.holdoutBefore.psnr,
                 r.holdoutAfter.psnr);
}

void printComparison(const subdfit::simplify::SimplifyReport& r) {
    std::fprintf(stderr, "shipped %s (%s): %s\n", r.route.path.string().c_str(), r.route.shipped.c_str(),
                 r.route.why.c_str());
    std::fprintf(stderr, "%-11s %10s %12s %8s %14s %12s\n", "", "bytes", "PSNR (dB)", "SSIM", "mean distance",
                 "Chamfer");
    auto row = [](const std::string& name, const subdfit::simplify::Quality* q) {
        if (!q) return;
        std::fprintf(stderr, "%-11s %10llu %12.2f %8.4f ", name.c_str(), (unsigned long long)q->bytes, q->psnrHoldout,
                     q->ssimHoldout);
        if (q->distance)
            std::fprintf(stderr, "%14.4e %12.4e\n", q->distance->meanDistance, q->distance->chamferL2Squared);
        else std::fprintf(stderr, "%14s %12s\n", subdfit::simplify::kNotMeasured, subdfit::simplify::kNotMeasured);
    };
    row("subdfit", &r.subdfit);
    // --prefix: what its first bytes decode to, the asset weighed against the baselines below.
    row(" its prefix", r.prefix && r.prefix->grown() ? &r.prefix->asset : nullptr);
    row("cage", r.cage ? &*r.cage : nullptr);
    for (const subdfit::simplify::MadeBaseline& b : r.triangles) row(b.name, &b.quality);
    row("bake", r.bake ? &*r.bake : nullptr);
    std::fprintf(stderr, "seconds by stage:");
    for (const auto& [stage, seconds] : r.stages.stages()) std::fprintf(stderr, " %s %.1f", stage.c_str(), seconds);
    std::fprintf(stderr, "\n");
}

void printProgress(const subdfit::fit::Progress& p) {
    std::fprintf(stderr, "step %d/%d  loss %.4e  %.1f s  ETA %.0f s\n", p.step, p.steps, double(p.loss), p.seconds,
                 p.etaSeconds);
}

}  // namespace

int main(int argc, char** argv) {
    subdfit::installStopSignals();  // first: a service may stop a run at any moment
    CLI::App app{"subdfit: fit Catmull-Clark cages (and maps) to renders of a reference"};
    app.require_subcommand(1);

    subdfit::fit::FitOptions fit;
    auto* fitCommand = app.add_subcommand("fit", "fit the control vertices of a cage to a reference mesh");
    subdfit::apps::addFitOptions(*fitCommand, fit);
    fitCommand->add_option("--out", fit.out, "output folder")->required();

    subdfit::simplify::SimplifyOptions simplify;
    auto* simplifyCommand =
        app.add_subcommand("simplify", "simplify a dense asset into a light cage and maps, with a quality report");
    simplifyCommand->add_option("reference", simplify.fit.reference, "dense reference asset (.obj, .gltf, .glb, .drc)")
        ->required();
    simplifyCommand->add_option("--out", simplify.fit.out, "output folder")->required();
    subdfit::apps::addSimplifySettings(*simplifyCommand, simplify);

    subdfit::simplify::SimplifyOptions batchDefaults;
    batchDefaults.compare = subdfit::simplify::CompareLevel::Fast;  // a batch compares less, by default
    std::filesystem::path manifest, batchOut;
    std::string shard = "0/1";
    auto* batchCommand = app.add_subcommand("batch", "simplify every asset of a manifest; resumable, shardable");
    batchCommand->add_option("manifest", manifest, "one asset a line: REFERENCE [simplify options]")->required();
    batchCommand->add_option("--out", batchOut, "output folder: one subfolder per asset")->required();
    batchCommand->add_option("--shard", shard, "run only assets k with k mod N = i (i/N, 0-based)")
        ->capture_default_str();
    subdfit::apps::addSimplifySettings(*batchCommand, batchDefaults);

    std::filesystem::path decodeInput, decodeOut;
    subdfit::exporter::EngineDecodeOptions decode;
    bool decodeUncompressed = false;
    auto* decodeCommand =
        app.add_subcommand("decode", "a shipped asset.subd back to triangles: the displaced limit surface as .glb");
    decodeCommand->add_option("file", decodeInput, "the .subd file")->required();
    decodeCommand->add_option("--out", decodeOut, "the .glb to write (a new file, or a regular file to replace)")
        ->required();
    auto* tess = decodeCommand->add_option("--tess", decode.density.segments, "segments per face edge, 1..64")
                     ->check(CLI::Range(1, subdfit::codec::kMaxDecodeSegments));
    auto* triangles =
        decodeCommand
            ->add_option("--triangles", decode.density.triangles,
                         "about this many triangles (default: the reference's, as asset.subd records it; at most " +
                             std::to_string(subdfit::codec::kMaxDecodeTriangles) + ")")
            ->check(CLI::Range(std::int64_t(1), subdfit::codec::kMaxDecodeTriangles))
            ->excludes(tess);
    const CLI::Validator errorBound(
        [](std::string& text) {
            std::string problem;
            return subdfit::apps::parseErrorBound(text, problem) ? std::string() : problem;
        },
        "DISTANCE");
    decodeCommand
        ->add_option_function<std::string>(
            "--max-error",
            [&decode](const std::string& text) {
                std::string problem;
                decode.maxError = subdfit::apps::parseErrorBound(text, problem);
            },
            "the coarsest density within this distance of the finest decode writes (asset units, or a percentage of "
            "the bounding box diagonal: 0.1%)")
        ->check(errorBound)
        ->excludes(tess)
        ->excludes(triangles);
    decodeCommand
        ->add_option(
            "--lods", decode.lods,
            "a chain of K levels of detail, about half the triangles each: OUT, OUT_lod1.glb ... and OUT_lods.json "
            "(triangles, bytes, distances, screen sizes)")
        ->check(CLI::Range(1, subdfit::exporter::kMostLods));
    decodeCommand
        ->add_option("--bytes", decode.firstBytes,
                     "decode only the file's first N bytes, as a stream delivers them: the cage and the map levels "
                     "wholly in them, a coarser asset")
        ->check(CLI::Range(std::size_t(1), std::numeric_limits<std::size_t>::max()));
    bool decodeMeshopt = false;
    decodeCommand->add_flag("--meshopt", decodeMeshopt,
                            "EXT_meshopt_compression besides KHR_mesh_quantization: smallest, for readers with "
                            "meshoptimizer's decoder (three.js with setMeshoptDecoder, gltfpack -c's readers)");
    decodeCommand
        ->add_flag("--uncompressed", decodeUncompressed,
                   "float attributes, no extension (what the web decoder's decode.mjs writes)")
        ->excludes("--meshopt");

    if (const auto exitCode = subdfit::apps::parseCommandLine(app, argc, argv, "subdfit")) return *exitCode;

    const auto say = [](const char* who) {
        return [who](const std::string& line) {
            std::fprintf(stderr, "%s: %s\n", who, subdfit::printable(line, 4096).c_str());
        };
    };
    // What an out-of-memory error is about: the file the command reads.
    const std::filesystem::path input = decodeCommand->parsed()     ? decodeInput
                                        : simplifyCommand->parsed() ? simplify.fit.reference
                                        : batchCommand->parsed()    ? manifest
                                                                    : fit.reference;
    try {
        const subdfit::fit::FitHooks hooks{
            .progress = printProgress, .cancel = &subdfit::stopRequest(), .note = say("subdfit")};
        if (decodeCommand->parsed()) {
            if (decodeUncompressed) decode.coding = subdfit::exporter::MeshCoding::Float;
            if (decodeMeshopt) decode.coding = subdfit::exporter::MeshCoding::Meshopt;
            for (const auto& written : subdfit::exporter::decodeForEngines(decodeInput, decodeOut, decode))
                std::cout << written.path.string() << "\n";
        }
        if (fitCommand->parsed()) {
            const auto report = subdfit::fit::runFit(fit, hooks);
            printSummary(report);
            std::cout << (fit.out / "report.json").string() << "\n";
        }
        if (simplifyCommand->parsed()) {
            const auto report = subdfit::simplify::runSimplify(simplify, hooks);
            if (report.fit) printSummary(*report.fit);
            printComparison(report);
            std::cout << (simplify.fit.out / "report.json").string() << "\n";
        }
        if (batchCommand->parsed()) {
            const auto parsedShard = subdfit::simplify::parseShard(shard);
            batchDefaults.fit.out = batchOut;  // each asset's own folder is set by the batch
            const auto items = subdfit::apps::readManifest(manifest, batchDefaults, say("batch"));
            const auto summary =
                subdfit::simplify::runBatch(items, batchOut, parsedShard, hooks, say("batch"), batchDefaults.fit.force);
            std::fprintf(
                stderr,
                "batch: %d finished, %d skipped (done), %d running elsewhere, %d failed, %d in other shards%s\n",
                summary.finished, summary.skipped, summary.runningElsewhere, summary.failed, summary.otherShards,
                summary.interrupted ? ", interrupted" : "");
            if (!summary.routes.empty()) {
                std::fprintf(stderr, "batch: routes shipped:");
                for (const auto& [route, count] : summary.routes) std::fprintf(stderr, " %s %d", route.c_str(), count);
                std::fprintf(stderr, "\n");
            }
            if (summary.failed > 0) return 1;
        }
    } catch (const subdfit::Interrupted& e) {
        std::fprintf(stderr, "subdfit: %s%s\n", e.what(), simplifyCommand->parsed() ? " (--resume continues)" : "");
        return 130;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "subdfit: error: %s: out of memory\n", subdfit::printable(input.string(), 4096).c_str());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "subdfit: error: %s\n", subdfit::printable(subdfit::apps::describeError(e), 4096).c_str());
        // An impossible option is a usage error, whether the parser or the core found it.
        return dynamic_cast<const subdfit::OptionError*>(&e) ? 2 : 1;
    }
    return subdfit::stopRequested() ? 130 : 0;
}
