// `subdfit-bench convergence`: a fit from a poor start, measured as it goes. A 216-quad sphere
// cage 30 % smaller than a lumpy sphere (the CPU peer's task: Mitsuba 3 + Large Steps reaches a
// symmetric Chamfer L2² of 7.07e-4 in 575 s on 2 cores), fitted with the options given (the
// fit's defaults unless told otherwise); the Chamfer of the cage's limit surface to the
// reference against the fit's own wall time, every few steps, as CSV and a plot.
#include <chrono>
#include <cstdio>

#include "bench_commands.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "fit/device_defaults.h"
#include "fit/fit_run.h"
#include "geometry/surface_distance.h"
#include "gl/platform_defines.h"
#include "mesh/mesh_geometry.h"
#include "mesh/procedural.h"
#include "plot.h"
#include "surface/tessellation.h"

namespace subdfit::bench {
namespace {

// The Chamfer in the reference's own units (the fit works in its normalised frame).
double chamfer(fit::FitRun& run, const mesh::PolygonMesh& referenceWorld, int samples) {
    mesh::PolygonMesh cage = run.scene().cage;
    cage.positions = run.scene().frame.toWorld(run.fitter().vertices());
    return geometry::surfaceDistance(surface::limitMesh(cage, 8), referenceWorld, samples).chamferL2Squared;
}

}  // namespace

int runConvergence(const ConvergenceOptions& o) {
    const auto reference = mesh::makeLumpySphere(5, o.amplitude, o.seed, o.bumps);
    mesh::PolygonMesh cage = mesh::makeQuadSphere(6);
    for (auto& p : cage.positions) p *= o.startScale;

    fit::FitOptions options = o.fit;
    options.out = o.out;
    auto context = context::createHeadlessContext(options.glProvider);
    if (const std::string chosen = fit::resolveForCurrentDevice(options); !chosen.empty())
        std::printf("%s\n", chosen.c_str());
    gl::ProgramCache programs(gl::platformDefines());
    fit::FitScene scene(fit::resolved(options), programs, cage, reference);
    fit::FitRun run(fit::resolved(options), programs, scene);
    std::printf("cage mean edge (normalised frame) %.4f\n", mesh::meanEdgeLength(scene.cage));

    std::printf(
        "convergence: %d-quad sphere cage at %.0f %% of a %d-triangle lumpy sphere; %d views at %d^2, %d steps\n",
        cage.faceCount(), 100.0 * o.startScale, reference.faceCount(), options.views, options.resolution,
        options.steps);
    std::printf("%8s %10s %14s\n", "step", "seconds", "chamfer L2^2");
    std::vector<std::vector<std::string>> rows{{"step", "seconds", "chamfer_l2sq"}};
    Series curve{.label = "subdfit, " + std::to_string(options.resolution) + "^2"};
    double seconds = 0.0, reached = -1.0;
    auto record = [&](int samples) {
        const double c = chamfer(run, reference, samples);
        std::printf("%8d %10.1f %14.3e\n", run.step(), seconds, c);
        std::fflush(stdout);
        rows.push_back({std::to_string(run.step()), std::to_string(seconds), std::to_string(c)});
        curve.x.push_back(std::max(seconds, 1e-2));
        curve.y.push_back(c);
        if (reached < 0.0 && c <= o.peerChamfer) reached = seconds;
        return c;
    };
    record(20000);
    while (!run.done()) {
        const auto start = std::chrono::steady_clock::now();
        run.runTo(std::min(run.step() + o.every, options.steps), o.out / "checkpoint.bin");
        glFinish();
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!run.done()) record(20000);
    }
    run.endStage();  // as `fit` does: back to the best monitored state if the last is not
    const double final = record(100000);

    std::filesystem::create_directories(o.out);
    writeCsv(o.out / "convergence.csv", rows);
    writePlot(o.out / "convergence.png", {.title = "Sphere cage at 70 % -> lumpy sphere: Chamfer against fit time",
                                          .xLabel = "fit seconds (this machine)",
                                          .yLabel = "symmetric Chamfer L2^2",
                                          .logX = true,
                                          .logY = true,
                                          .series = {curve, Series{.label = "peer (Mitsuba 3 + Large Steps, 575 s)",
                                                                   .x = {575.0},
                                                                   .y = {o.peerChamfer},
                                                                   .markersOnly = true}}});
    std::printf("peer chamfer %.2e %s\n", o.peerChamfer,
                reached >= 0.0 ? ("reached after " + std::to_string(reached) + " s").c_str() : "not reached");
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("fit_seconds=%.1f chamfer_l2sq=%.3e steps=%d stop=%s\n", seconds, final, run.step(),
                fit::toString(run.stopReason()));
    return 0;
}

}  // namespace subdfit::bench
