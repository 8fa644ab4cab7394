// `subdfit-bench simplify`: what a simplified asset's bytes buy. For each dense reference and
// byte budget, `subdfit simplify --budget` and its baselines at the same bytes (decimation +
// Draco, gltfpack when installed, the bake route); plotted as held-out PSNR and symmetric mean
// surface distance against bytes, one pair of plots per reference; and where the bytes of each
// asset.subd it wrote go (the shipped one, the bake baseline's): cage connectivity, positions,
// polygon marks, tags and each map, with the cage's faces, quads and regular vertices; and where
// a cage shipped, its held-out PSNR as fitted, before coding (what the cage and maps could reach
// unquantised) beside what the file draws.
#include <cstdio>
#include <map>
#include <optional>

#include "bench_commands.h"
#include "bench_common.h"
#include "plot.h"
#include "subd_bytes.h"
#include "simplify/simplify_job.h"

namespace subdfit::bench {
namespace {

// The default dense reference: the relief Spot (surface/relief_surface.h), written once.
std::filesystem::path reliefReference(const std::filesystem::path& out) {
    ReliefOptions relief;
    relief.out = out / "relief_spot.glb";
    if (!std::filesystem::exists(relief.out)) writeReliefReference(relief);
    return relief.out;
}

}  // namespace

int runSimplifyTradeoff(const SimplifyTradeoffOptions& o) {
    std::filesystem::create_directories(o.out);
    std::vector<std::filesystem::path> references = o.references;
    if (references.empty()) references.push_back(reliefReference(o.out));
    std::vector<std::vector<std::string>> rows{{"reference", "budget", "method", "bytes", "psnr_holdout",
                                                "ssim_holdout", "mean_distance", "chamfer", "hausdorff", "seconds",
                                                "chosen", "psnr_holdout_unquantised"}};
    std::vector<std::vector<std::string>> stageRows{{"reference", "budget", "route", "stage", "seconds"}};
    std::vector<std::vector<std::string>> byteRows{{"reference", "budget", "file", "bytes", "faces", "quads",
                                                    "vertices", "position_bits", "regular_vertices",
                                                    "cage_connectivity", "cage_positions", "cage_polygon_marks",
                                                    "cage_tags", "cage_section", "maps", "cage_bytes_per_face"}};
    std::printf("%-18s %8s  %-10s %8s %9s %7s %13s %9s  %s\n", "reference", "budget", "method", "bytes", "PSNR dB",
                "SSIM", "mean distance", "seconds", "chosen");
    for (const auto& reference : references) {
        const std::string name = reference.stem().string();
        std::map<std::string, Series> psnr, distance;
        for (const std::uintmax_t budget : o.budgets) {
            simplify::SimplifyOptions s;
            s.budget = budget;
            s.fit.reference = reference;
            s.fit.out = o.out / (name + "_" + std::to_string(budget));
            s.fit.steps = o.steps;
            s.fit.resolution = o.resolution;
            s.fit.glProvider = o.glProvider;
            s.fit.force = true;
            s.compare = o.compare;
            s.cageShape = o.cageShape;
            const auto report = simplify::runSimplify(s);
            const std::optional<double> unquantised = simplify::unquantisedPsnr(report);
            std::string choice = report.route.shipped;
            if (report.route.shipped == "cage" && report.budget) {
                const simplify::BudgetCandidate& chosen = report.budget->chosen;
                choice = std::to_string(chosen.faces) + " faces, " + maps::toString(chosen.maps) +
                         " T=" + std::to_string(chosen.mapResolution) + " at " + std::to_string(chosen.mapBits) +
                         " bits, " + std::to_string(chosen.positionBits) + "-bit positions";
            }
            std::vector<std::pair<std::string, const simplify::Quality*>> methods{{"subdfit", &report.subdfit}};
            if (report.cage) methods.emplace_back("cage", &*report.cage);
            for (const simplify::MadeBaseline& b : report.triangles)
                if (b.name != "decimation" || o.compare != simplify::CompareLevel::None)
                    methods.emplace_back(b.name, &b.quality);
            if (report.bake) methods.emplace_back("bake", &*report.bake);
            for (const auto& [method, q] : methods) {
                const double seconds = method == "subdfit" ? report.seconds : 0.0;
                const geometry::SurfaceDistance d =
                    q->distance.value_or(geometry::SurfaceDistance{});  // --compare full: measured
                const std::string chosenText = method == "subdfit" ? choice : "";
                char unquantisedText[40] = "";
                const bool withUnquantised = method == "subdfit" && unquantised;
                if (withUnquantised)
                    std::snprintf(unquantisedText, sizeof unquantisedText, " (%.2f dB unquantised)", *unquantised);
                std::printf("%-18.18s %8ju  %-10s %8ju %9.2f %7.4f %13.4e %9.1f  %s%s\n", name.c_str(), budget,
                            method.c_str(), q->bytes, q->psnrHoldout, q->ssimHoldout, d.meanDistance, seconds,
                            chosenText.c_str(), unquantisedText);
                std::fflush(stdout);
                rows.push_back({name, std::to_string(budget), method, std::to_string(q->bytes),
                                std::to_string(q->psnrHoldout), std::to_string(q->ssimHoldout),
                                std::to_string(d.meanDistance), std::to_string(d.chamferL2Squared),
                                std::to_string(d.hausdorff), std::to_string(seconds), chosenText,
                                withUnquantised ? std::to_string(*unquantised) : ""});
                // A decimation that fits the whole reference is lossless (PSNR capped at 120 dB):
                // in the CSV, off the plots, whose scale it would flatten.
                if (q->psnrHoldout >= 100.0) continue;
                for (auto* series : {&psnr, &distance}) {
                    (*series)[method].label = method;
                    (*series)[method].x.push_back(double(q->bytes));
                }
                psnr[method].y.push_back(q->psnrHoldout);
                distance[method].y.push_back(d.meanDistance);
            }
            // Where the seconds went, stage by stage.
            std::printf("%-18.18s %8ju  seconds by stage:", name.c_str(), budget);
            for (const auto& [stage, seconds] : report.stages.stages()) {
                std::printf(" %s %.1f", stage.c_str(), seconds);
                stageRows.push_back(
                    {name, std::to_string(budget), report.route.shipped, stage, std::to_string(seconds)});
            }
            std::printf(" (total %.1f)\n", report.seconds);
            for (const char* file : {"asset.subd", "baselines/bake/asset.subd"}) {
                if (!std::filesystem::exists(s.fit.out / file)) continue;
                const SubdBytes b = subdBytes(s.fit.out / file);
                std::size_t maps = 0;
                for (const auto& [tag, bytes] : b.sections) maps += tag == "CAGE" ? 0 : bytes;
                const std::size_t cage = b.sections.count("CAGE") ? b.sections.at("CAGE") : 0;
                std::printf(
                    "%-18.18s %8ju  %s: %ju B; cage %d faces (%d quads), %d vertices (%d regular) at %d bits: "
                    "connectivity %zu, positions %zu, polygon marks %zu, tags %zu (section %zu, %.2f B a face); maps "
                    "%zu\n",
                    name.c_str(), budget, file, std::uintmax_t(b.file), b.faces, b.quads, b.vertices, b.regularVertices,
                    b.positionBits, b.cage.connectivity, b.cage.positions, b.cage.polygonMarks, b.cage.tags, cage,
                    double(cage) / std::max(b.faces, 1), maps);
                byteRows.push_back({name, std::to_string(budget), file, std::to_string(b.file), std::to_string(b.faces),
                                    std::to_string(b.quads), std::to_string(b.vertices), std::to_string(b.positionBits),
                                    std::to_string(b.regularVertices), std::to_string(b.cage.connectivity),
                                    std::to_string(b.cage.positions), std::to_string(b.cage.polygonMarks),
                                    std::to_string(b.cage.tags), std::to_string(cage), std::to_string(maps),
                                    std::to_string(double(cage) / std::max(b.faces, 1))});
            }
            writeCsv(o.out / "simplify_tradeoff.csv", rows);  // after every run: a long sweep keeps what it did
            writeCsv(o.out / "simplify_stages.csv", stageRows);
            writeCsv(o.out / "simplify_bytes.csv", byteRows);
        }
        auto plot = [&](const std::string& file, const char* yLabel, bool logY, std::map<std::string, Series>& series) {
            PlotSpec spec;
            spec.title = "simplify " + name + ": held-out views, at equal bytes";
            spec.xLabel = "bytes shipped";
            spec.yLabel = yLabel;
            spec.logX = true;
            spec.logY = logY;
            for (auto& [method, s] : series) spec.series.push_back(s);
            writePlot(o.out / file, spec);
        };
        plot(name + "_psnr_vs_bytes.png", "PSNR (dB)", false, psnr);
        plot(name + "_distance_vs_bytes.png", "mean surface distance (reference units)", true, distance);
    }
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
