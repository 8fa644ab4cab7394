// `subdfit-bench simplify`: what a simplified asset's bytes buy. For each cage size and map
// resolution, `subdfit simplify` and its two baselines at the same bytes; plotted as held-out
// PSNR and Chamfer against bytes, so the crossover with plain decimation is visible.
#include <cstdio>
#include <map>

#include "bench_commands.h"
#include "bench_common.h"
#include "plot.h"
#include "simplify/simplify_job.h"

namespace subdfit::bench {

int runSimplifyTradeoff(const SimplifyTradeoffOptions& o) {
    std::filesystem::create_directories(o.out);
    std::vector<std::vector<std::string>> rows{{"faces", "maps", "method", "bytes", "psnr_holdout", "chamfer",
                                                "hausdorff", "seconds"}};
    std::map<std::string, Series> psnr, chamfer;
    auto add = [&](const std::string& series, double bytes, double p, double c) {
        psnr[series].label = chamfer[series].label = series;
        psnr[series].markersOnly = chamfer[series].markersOnly = series == "decimation" || series == "bake";
        psnr[series].x.push_back(bytes), psnr[series].y.push_back(p);
        chamfer[series].x.push_back(bytes), chamfer[series].y.push_back(c);
    };
    std::printf("%6s %5s  %-11s %10s %10s %12s %9s\n", "faces", "maps", "method", "bytes", "PSNR dB", "Chamfer", "seconds");
    for (const std::string& maps : o.maps)
        for (int faces : o.faces) {
            simplify::SimplifyOptions s;
            s.faces = faces;
            s.fit.reference = o.reference;
            s.fit.out = o.out / ("faces" + std::to_string(faces) + "_maps" + maps);
            s.fit.steps = o.steps;
            s.fit.resolution = o.resolution;
            s.fit.glProvider = o.glProvider;
            s.fit.maps = maps::parseMapEffects(maps == "none" ? "none" : "displacement,normal");
            if (maps != "none") s.fit.mapResolution = std::stoi(maps);
            const auto report = simplify::runSimplify(s);
            const std::string ours = maps == "none" ? "subdfit, no maps" : "subdfit, maps T=" + maps;
            const std::pair<std::string, const simplify::Quality*> methods[] = {
                {ours, &report.subdfit}, {"decimation", &report.decimation}, {"bake", &report.bake}};
            for (const auto& [name, q] : methods) {
                const double bytes = double(q->bytes);
                const double p = q->psnrHoldout, c = q->distance.chamferL2Squared;
                const double seconds = name == ours ? report.fit.seconds : 0.0;
                std::printf("%6d %5s  %-11.11s %10.0f %10.2f %12.4e %9.1f\n", faces, maps.c_str(), name.c_str(), bytes,
                            p, c, seconds);
                rows.push_back({std::to_string(faces), maps, name, std::to_string(bytes), std::to_string(p),
                                std::to_string(c), std::to_string(q->distance.hausdorff),
                                std::to_string(seconds)});
                // A decimation that fits the whole reference in the budget is lossless (PSNR capped
                // at 120 dB): in the CSV, but off the plots, whose scale it would flatten.
                if (p < 100.0) add(name, bytes, p, c);
            }
        }
    writeCsv(o.out / "simplify_tradeoff.csv", rows);
    auto plot = [&](const char* file, const char* yLabel, bool logY, std::map<std::string, Series>& series) {
        PlotSpec spec;
        spec.title = "simplify: " + o.reference.filename().string() + ", held-out views";
        spec.xLabel = "bytes shipped";
        spec.yLabel = yLabel;
        spec.logX = true;
        spec.logY = logY;
        for (auto& [name, s] : series) spec.series.push_back(s);
        writePlot(o.out / file, spec);
    };
    plot("psnr_vs_bytes.png", "PSNR (dB)", false, psnr);
    plot("chamfer_vs_bytes.png", "Chamfer (reference units^2)", true, chamfer);
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
