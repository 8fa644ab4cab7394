// `subdfit-bench fit-gain`: what the fit adds to a good start, per second. One cage (a simplify
// candidate: limit-fitted, optionally with maps baked onto it and then refined on the frozen cage,
// as simplify does) on one dense reference; each variant (fit options over the common ones) is a
// run of its own, and the runs take turns a few steps at a time, so the machine's load falls on
// all of them alike. Held-out PSNR against each run's own fit seconds, as CSV and a plot.
#include <chrono>
#include <cstdio>
#include <sstream>

#include "bench_commands.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "fit/device_defaults.h"
#include "fit/fit_run.h"
#include "gl/platform_defines.h"
#include "mesh/mesh_loader.h"
#include "plot.h"
#include "simplify/bake/bake.h"
#include "simplify/cage/initial_cage.h"

namespace subdfit::bench {
namespace {

// "key=value;key=value" over `base`.
fit::FitOptions variantOptions(const fit::FitOptions& base, const std::string& variant) {
    fit::FitOptions options = base;
    std::stringstream items(variant);
    std::string item;
    while (std::getline(items, item, ';')) {
        if (item.empty()) continue;
        const auto eq = item.find('=');
        if (eq == std::string::npos) throw OptionError("variant", "'" + item + "' is not key=value");
        fit::setOption(options, item.substr(0, eq), item.substr(eq + 1));
    }
    return options;
}

struct Contender {
    std::string name;
    std::unique_ptr<fit::FitRun> run;
    double seconds = 0.0;
    Series curve;
};

// What simplify does with baked maps: the cage frozen, the maps refined with small steps.
constexpr float kRefineRate = 0.02f;

}  // namespace

int runFitGain(const FitGainOptions& o) {
    fit::FitOptions base = o.fit;
    base.out = o.out;
    auto context = context::createHeadlessContext(base.glProvider);
    if (const std::string chosen = fit::resolveForCurrentDevice(base); !chosen.empty())
        std::printf("%s\n", chosen.c_str());
    gl::ProgramCache programs(gl::platformDefines());
    const mesh::PolygonMesh reference = mesh::loadReference(o.reference);
    const mesh::PolygonMesh cage =
        o.faces > 0 ? simplify::initialCage(reference, {.faces = o.faces}) : mesh::loadMesh(o.cage);
    fit::FitScene scene(fit::resolved(base), programs, cage, reference);
    const bool baked = base.maps.geometric();
    surface::SurfaceMaps maps;
    if (baked) {
        base.mapsStart = 0.0f;
        maps =
            simplify::bakeMaps(scene.cage, scene.reference, {.effects = base.maps, .resolution = base.mapResolution});
    }
    std::vector<Contender> contenders;
    for (const auto& variant : o.variants.empty() ? std::vector<std::string>{""} : o.variants) {
        fit::FitOptions options = variantOptions(base, variant);
        options.out = o.out / ("run" + std::to_string(contenders.size()));
        std::filesystem::remove(options.out / "checkpoint.bin");
        auto run = std::make_unique<fit::FitRun>(fit::resolved(options), programs, scene);
        if (baked) {
            run->startFrom(maps);
            auto& fitter = run->fitter();
            fitter.setOptimised(fitter.vertexGroup(), false);
            for (auto* g : fitter.maps()->groups())
                fitter.setRates(*g, g->settings().epsilon, kRefineRate * g->settings().learningRate);
        }
        const std::string name = variant.empty() ? "defaults" : variant;
        contenders.push_back({name, std::move(run), 0.0, Series{.label = name}});
    }
    std::printf("fit-gain: %s on %s (%d faces, %d-triangle reference), maps %s; %d views at %d^2, at most %d steps\n",
                o.faces > 0 ? "simplify's initial cage" : o.cage.filename().c_str(), o.reference.filename().c_str(),
                scene.cage.faceCount(), scene.reference.faceCount(), maps::toString(base.maps).c_str(), base.views,
                base.resolution, base.steps);
    std::vector<std::vector<std::string>> rows{{"variant", "step", "seconds", "psnr_holdout", "gain_db"}};
    std::vector<double> start;
    auto record = [&](Contender& c) {
        const double psnr = fit::score(c.run->fitter(), scene.holdout).psnr;
        if (start.size() < contenders.size()) start.push_back(psnr);
        const double gain = psnr - start[size_t(&c - contenders.data())];
        rows.push_back({c.name, std::to_string(c.run->step()), std::to_string(c.seconds), std::to_string(psnr),
                        std::to_string(gain)});
        std::printf("  %-40s step %5d %8.1f s  %8.3f dB  %+.3f\n", c.name.c_str(), c.run->step(), c.seconds, psnr,
                    gain);
        std::fflush(stdout);
        c.curve.x.push_back(c.seconds);
        c.curve.y.push_back(gain);
        return psnr;
    };
    for (auto& c : contenders) record(c);
    for (bool any = true; any;) {
        any = false;
        for (auto& c : contenders) {
            if (c.run->done()) continue;
            any = true;
            const auto began = std::chrono::steady_clock::now();
            c.run->runTo(c.run->step() + o.every, c.run->options().out / "checkpoint.bin");
            glFinish();
            c.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
            if (!c.run->done()) record(c);
        }
    }
    std::printf("%-40s %6s %9s %10s %10s %8s  %s\n", "variant", "steps", "fit s", "PSNR in", "PSNR out", "gain dB",
                "stop");
    for (auto& c : contenders) {
        c.run->endStage();
        const double psnr = record(c);
        const double before = start[size_t(&c - contenders.data())];
        std::printf("%-40s %6d %9.1f %10.3f %10.3f %+8.3f  %s\n", c.name.c_str(), c.run->step(), c.seconds, before,
                    psnr, psnr - before, fit::toString(c.run->stopReason()));
    }
    std::filesystem::create_directories(o.out);
    writeCsv(o.out / "fit_gain.csv", rows);
    std::vector<Series> series;
    for (auto& c : contenders) series.push_back(c.curve);
    writePlot(o.out / "fit_gain.png", {.title = "Fit from a good start: held-out gain against fit time",
                                       .xLabel = "fit seconds (this machine)",
                                       .yLabel = "held-out PSNR gain (dB)",
                                       .series = series});
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
