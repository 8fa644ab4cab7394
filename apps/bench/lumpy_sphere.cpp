// `subdfit-bench lumpy-sphere`: the task the CPU peer was measured on (Mitsuba 3 + Large Steps,
// 575 s on 2 cores to a symmetric Chamfer L2² of 7.1e-4): fit a ~200-quad sphere cage to a
// lumpy sphere at 256², 8 views, and report time and geometric error in the sphere's own units.
#include <cstdio>

#include "bench_commands.h"
#include "bench_common.h"
#include "fit/fit_job.h"
#include "surface/tessellation.h"
#include "geometry/surface_distance.h"
#include "mesh/mesh_loader.h"
#include "mesh/obj_writer.h"
#include "mesh/procedural.h"

namespace subdfit::bench {

int runLumpySphere(const LumpySphereOptions& o) {
    std::filesystem::create_directories(o.out);
    const auto reference = mesh::makeLumpySphere(5, o.amplitude, o.lumpsSeed, o.bumps);
    const auto cage = mesh::makeQuadSphere(o.cageDivisions);
    mesh::writeObj(o.out / "lumpy_sphere.obj", reference);
    mesh::writeObj(o.out / "quad_sphere_cage.obj", cage);

    const auto before = geometry::surfaceDistance(surface::limitMesh(cage, 8), reference);
    fit::FitOptions fit;
    fit.cage = o.out / "quad_sphere_cage.obj";
    fit.reference = o.out / "lumpy_sphere.obj";
    fit.out = o.out / "fit";
    fit.steps = o.steps;
    fit.noiseGate = o.noiseGate;
    fit.resolution = o.resolution;
    fit.views = o.views;
    fit.glProvider = o.glProvider;
    fit.seed = o.seed;
    fit.force = true;
    const auto report = fit::runFit(fit, {.progress = [](const fit::Progress& p) {
                                        std::fprintf(stderr, "step %d/%d  loss %.4e  %.1f s  ETA %.0f s\n", p.step,
                                                     p.steps, double(p.loss), p.seconds, p.etaSeconds);
                                    }});
    const auto fitted = mesh::loadMesh(fit.out / "cage.obj");
    const auto after = geometry::surfaceDistance(surface::limitMesh(fitted, 8), reference);

    std::printf("lumpy sphere: %d-face cage, %d-triangle reference, %d views at %d^2, %d steps (%s)\n",
                cage.faceCount(), reference.faceCount(), o.views, o.resolution, report.steps,
                report.stopReason.c_str());
    std::printf("%-8s %14s %14s %12s\n", "", "chamfer L2^2", "mean dist", "hausdorff");
    std::printf("%-8s %14.3e %14.3e %12.3e\n", "before", before.chamferL2Squared, before.meanDistance,
                before.hausdorff);
    std::printf("%-8s %14.3e %14.3e %12.3e\n", "after", after.chamferL2Squared, after.meanDistance, after.hausdorff);
    std::printf("fit_seconds=%.1f total_seconds=%.1f cpu_seconds=%.1f psnr_holdout=%.2f\n", report.fitSeconds,
                report.seconds, processCpuSeconds(), report.holdoutAfter.psnr);
    writeCsv(o.out / "lumpy_sphere.csv",
             {{"stage", "seconds", "chamfer_l2sq", "mean_distance", "hausdorff", "psnr_holdout"},
              {"before", "0", std::to_string(before.chamferL2Squared), std::to_string(before.meanDistance),
               std::to_string(before.hausdorff), std::to_string(report.holdoutBefore.psnr)},
              {"after", std::to_string(report.fitSeconds), std::to_string(after.chamferL2Squared),
               std::to_string(after.meanDistance), std::to_string(after.hausdorff),
               std::to_string(report.holdoutAfter.psnr)}});
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("chamfer_l2sq=%.3e\n", after.chamferL2Squared);
    return 0;
}

}  // namespace subdfit::bench
