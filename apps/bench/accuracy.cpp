// `subdfit-bench accuracy`: what accuracy costs in time. Sweeps the knobs a user trades (steps,
// render resolution, views and perturbation samples per step, tessellation level, map
// resolution) one at a time around a base setting, on two assets: a lumpy sphere (cage only)
// and a bumpy sphere (cage + displacement map), both over the ~200-quad sphere cage. Each run
// reports held-out PSNR and the symmetric Chamfer distance of what it ships (asset.subd,
// decoded) to the reference, against its wall time; plots mark the Pareto front.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "export/engine/subd_decode.h"
#include "bench_commands.h"
#include "bench_common.h"
#include "fit/fit_job.h"
#include "geometry/surface_distance.h"
#include "io/atomic_file.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"
#include "plot.h"

namespace subdfit::bench {
namespace {

struct Knob {
    std::string name;
    std::vector<int> values;
    void (*apply)(fit::FitOptions&, int);
};

struct Result {
    std::string asset, knob;
    int value;
    double seconds, psnr, chamfer;
};

std::vector<std::pair<double, double>> paretoFront(std::vector<std::pair<double, double>> points) {
    // Lower time and lower Chamfer are both better.
    std::sort(points.begin(), points.end());
    std::vector<std::pair<double, double>> front;
    for (const auto& p : points)
        if (front.empty() || p.second < front.back().second) front.push_back(p);
    return front;
}

}  // namespace

int runAccuracy(const AccuracyOptions& o) {
    std::filesystem::create_directories(o.out);
    const auto cagePath = o.out / "quad_sphere_cage.obj";
    mesh::writeObj(cagePath, mesh::makeQuadSphere(6));
    struct Asset {
        std::string name, maps;
        mesh::PolygonMesh reference;
    };
    std::vector<Asset> assets{{"lumpy", "none", mesh::makeLumpySphere(5, 0.15f, 1)},
                              {"bumpy", "displacement", mesh::makeLumpySphere(6, 0.04f, 3, 150, 0.002f, 0.01f)}};

    const std::vector<Knob> knobs{
        {"steps", {50, 100, 200, 400, 800}, [](fit::FitOptions& f, int v) { f.steps = v; }},
        {"resolution", {128, 512}, [](fit::FitOptions& f, int v) { f.resolution = v; }},
        {"views_per_step", {2, 4}, [](fit::FitOptions& f, int v) { f.viewsPerStep = v; }},
        {"samples_per_step", {2, 4}, [](fit::FitOptions& f, int v) { f.samplesPerStep = v; }},
        {"tess", {4, 16}, [](fit::FitOptions& f, int v) { f.tessLevel = v; }},
        {"map_res", {4, 16}, [](fit::FitOptions& f, int v) { f.mapResolution = v; }},
    };

    std::vector<Result> results;
    std::vector<std::vector<std::string>> rows{{"asset", "knob", "value", "seconds", "psnr_holdout", "chamfer_l2sq"}};
    std::printf("%-7s %-17s %6s %9s %9s %13s\n", "asset", "knob", "value", "fit s", "PSNR", "chamfer L2^2");
    for (const auto& asset : assets) {
        const auto referencePath = o.out / (asset.name + "_reference.obj");
        mesh::writeObj(referencePath, asset.reference);
        for (const auto& knob : knobs) {
            if (knob.name == "map_res" && asset.maps == "none") continue;
            for (int value : knob.values) {
                fit::FitOptions fit;
                fit.cage = cagePath;
                fit.reference = referencePath;
                fit.maps = maps::parseMapEffects(asset.maps);
                fit.steps = o.baseSteps;
                fit.glProvider = o.glProvider;
                knob.apply(fit, value);
                fit.out = o.out / "runs" / (asset.name + "_" + knob.name + "_" + std::to_string(value));
                const auto report = fit::runFit(fit);
                const auto decoded =
                    exporter::decodeToGlb(fit.out / "asset.subd", fit.out / "decoded.glb", {.segments = fit.tessLevel});
                const auto shipped = mesh::triangulated(mesh::loadMesh(decoded.path));
                const double chamfer = geometry::surfaceDistance(shipped, asset.reference, 50000).chamferL2Squared;
                const Result r{asset.name, knob.name, value, report.fitSeconds, report.holdoutAfter.psnr, chamfer};
                std::printf("%-7s %-17s %6d %9.1f %9.2f %13.3e\n", r.asset.c_str(), r.knob.c_str(), r.value, r.seconds,
                            r.psnr, r.chamfer);
                std::fflush(stdout);
                results.push_back(r);
                rows.push_back({r.asset, r.knob, std::to_string(r.value), std::to_string(r.seconds),
                                std::to_string(r.psnr), std::to_string(r.chamfer)});
            }
        }
    }
    writeCsv(o.out / "accuracy.csv", rows);

    // Plots per asset: Chamfer and PSNR against time, one series per knob, the front on top.
    std::string summary = "# subdfit-bench accuracy\n\nBase: " + std::to_string(o.baseSteps) +
                          " steps, 256², 24 views, 1 view and 1 sample per step, tess 8, map-res 8; each row changes "
                          "one knob. Times are wall seconds of the fit loop on this machine (llvmpipe); compare "
                          "them only within this run.\n";
    for (const auto& asset : assets) {
        std::map<std::string, Series> chamferSeries, psnrSeries;
        std::vector<std::pair<double, double>> points;
        const Result* base = nullptr;
        for (const auto& r : results) {
            if (r.asset != asset.name) continue;
            if (r.knob == "steps" && r.value == o.baseSteps) base = &r;
            auto& c = chamferSeries[r.knob];
            auto& p = psnrSeries[r.knob];
            c.label = p.label = r.knob;
            c.markersOnly = p.markersOnly = r.knob != "steps";
            c.x.push_back(r.seconds), c.y.push_back(r.chamfer);
            p.x.push_back(r.seconds), p.y.push_back(r.psnr);
            points.push_back({r.seconds, r.chamfer});
        }
        PlotSpec chamfer;
        chamfer.title = asset.name + " sphere: geometric error against time";
        chamfer.xLabel = "fit seconds";
        chamfer.yLabel = "symmetric Chamfer L2^2";
        chamfer.logX = chamfer.logY = true;
        for (auto& [name, series] : chamferSeries) chamfer.series.push_back(series);
        chamfer.highlight = paretoFront(points);
        writePlot(o.out / (asset.name + "_chamfer_vs_time.png"), chamfer);
        PlotSpec psnr = chamfer;
        psnr.title = asset.name + " sphere: held-out PSNR against time";
        psnr.yLabel = "held-out PSNR (dB)";
        psnr.logY = false;
        psnr.series.clear();
        psnr.highlight.clear();
        for (auto& [name, series] : psnrSeries) psnr.series.push_back(series);
        writePlot(o.out / (asset.name + "_psnr_vs_time.png"), psnr);

        // Which knob buys the most accuracy per second: for each change from the base, how much
        // Chamfer it removes (log) per second it adds, or the time it saves at what cost.
        summary += "\n## " + asset.name + " sphere (" + (asset.maps == "none" ? "cage only" : "cage + displacement") +
                   ")\n\n| knob | value | fit s | PSNR | Chamfer | vs base: Δ log10 Chamfer per added second |\n"
                   "|---|---|---|---|---|---|\n";
        const Result* bestBuy = nullptr;  // the change from base that removes most error per added second
        double bestRate = 0.0;
        for (const auto& r : results) {
            if (r.asset != asset.name) continue;
            std::string rate = "—";
            if (base && &r != base && std::abs(r.seconds - base->seconds) > 0.5) {
                const double perSecond =
                    (std::log10(base->chamfer) - std::log10(r.chamfer)) / (r.seconds - base->seconds);
                char text[64];
                std::snprintf(text, sizeof text, "%+.4f", perSecond);
                rate = text;
                if (r.seconds > base->seconds && perSecond > bestRate) bestRate = perSecond, bestBuy = &r;
            }
            char line[256];
            std::snprintf(line, sizeof line, "| %s | %d | %.1f | %.2f | %.3e | %s |\n", r.knob.c_str(), r.value,
                          r.seconds, r.psnr, r.chamfer, rate.c_str());
            summary += line;
        }
        if (bestBuy) {
            char verdict[256];
            std::snprintf(verdict, sizeof verdict,
                          "\n**Most accuracy per second from the base:** %s = %d (%.3f decades of Chamfer per "
                          "added second; %.1f s, Chamfer %.2e, PSNR %.2f dB).\n",
                          bestBuy->knob.c_str(), bestBuy->value, bestRate, bestBuy->seconds, bestBuy->chamfer,
                          bestBuy->psnr);
            summary += verdict;
        }
        summary += "\nPareto front (time, Chamfer): ";
        for (const auto& [t, c] : chamfer.highlight) {
            for (const auto& r : results)
                if (r.asset == asset.name && r.seconds == t && r.chamfer == c) {
                    char text[96];
                    std::snprintf(text, sizeof text, "%s=%d (%.1f s, %.2e); ", r.knob.c_str(), r.value, t, c);
                    summary += text;
                }
        }
        summary += "\n";
    }
    // The per-step cost, measured in this same run, completes the picture.
    runStepCost({.out = o.out / "step-cost", .repeats = 7, .glProvider = o.glProvider});
    std::ifstream stepCost(o.out / "step-cost" / "step_cost.md");
    summary += "\n" + std::string(std::istreambuf_iterator<char>(stepCost), {});
    io::writeTextAtomically(o.out / "summary.md", summary);
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("summary=%s\n", (o.out / "summary.md").string().c_str());
    return 0;
}

}  // namespace subdfit::bench
