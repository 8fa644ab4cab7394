// `subdfit-bench maps`: what the displacement and normal maps buy over a vertex-only fit, on a
// reference with detail far finer than the cage can express (a sphere covered in small bumps,
// over the ~200-quad sphere cage): held-out PSNR, time and the size of what a user ships.
#include <cstdio>

#include "bench_commands.h"
#include "bench_common.h"
#include "fit/fit_job.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"

namespace subdfit::bench {

int runMapsGain(const MapsGainOptions& o) {
    std::filesystem::create_directories(o.out);
    mesh::writeObj(o.out / "bumpy_sphere.obj", mesh::makeLumpySphere(6, 0.04f, 3, 150, 0.002f, 0.01f));
    mesh::writeObj(o.out / "quad_sphere_cage.obj", mesh::makeQuadSphere(6));

    struct Run {
        std::string maps;
        bool draco;
    };
    const Run runs[] = {{"none", false}, {"displacement", false}, {"displacement,normal", false},
                        {"displacement,normal", true}};
    std::vector<std::vector<std::string>> rows{
        {"maps", "draco", "steps", "fit_seconds", "psnr_holdout_initial", "psnr_holdout", "cage_bytes", "maps_bytes",
         "glb_bytes", "parameters"}};
    std::printf("%-22s %6s %8s %10s %12s %10s %10s %11s\n", "maps", "draco", "fit s", "PSNR in", "PSNR out",
                "cage B", "maps B", "glb B");
    for (const auto& run : runs) {
        fit::FitOptions fit;
        fit.cage = o.out / "quad_sphere_cage.obj";
        fit.reference = o.out / "bumpy_sphere.obj";
        fit.out = o.out / (run.maps + (run.draco ? "_draco" : ""));
        fit.steps = o.steps;
        fit.maps = maps::parseMapEffects(run.maps);
        fit.mapResolution = o.mapResolution;
        fit.draco = run.draco;
        fit.glProvider = o.glProvider;
        const auto report = fit::runFit(fit);
        const auto& exports = report.exports;
        std::uintmax_t mapsBytes = 0;
        for (const char* name : {"displacement.exr", "normal.png"})
            if (exports.count(name)) mapsBytes += exports.at(name);
        const auto cageBytes = std::filesystem::file_size(fit.out / "cage.obj");
        int parameters = 0;
        for (const auto& [group, count] : report.parameters) parameters += count;
        std::printf("%-22s %6s %8.1f %10.2f %12.2f %10ju %10ju %11ju\n", run.maps.c_str(), run.draco ? "yes" : "no",
                    report.fitSeconds, report.holdoutBefore.psnr,
                    report.holdoutAfter.psnr, cageBytes, mapsBytes,
                    exports.at("fitted.glb"));
        rows.push_back({run.maps, run.draco ? "1" : "0", std::to_string(report.steps),
                        std::to_string(report.fitSeconds),
                        std::to_string(report.holdoutBefore.psnr),
                        std::to_string(report.holdoutAfter.psnr), std::to_string(cageBytes),
                        std::to_string(mapsBytes), std::to_string(exports.at("fitted.glb")),
                        std::to_string(parameters)});
    }
    writeCsv(o.out / "maps_gain.csv", rows);
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
