// `subdfit-bench step-cost`: one SGE step's time over one forward render's time, measured in the
// same run (two renders are the floor, so the goal is <= 2.2), at a few resolutions; and how the
// step time scales with the number of parameters.
#include <glad/gl.h>

#include <cstdio>

#include "bench_common.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "bench_commands.h"
#include "context/gl_context.h"
#include "fit/cage_fitter.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "render/mesh_renderer.h"

namespace subdfit::bench {
namespace {

struct Timing {
    double renderMs, stepMs;
    double accumulateMs, updateMs;  // the step's halves: P + 2R + G, then preconditioner + Adam
};

Timing timeCage(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const render::MeshRenderer& reference,
                int resolution, int repeats) {
    const scene::TargetSet targets(programs, reference, render::orbitCameras(8, 1), resolution);
    fit::CageFitSettings settings;
    settings.resolution = resolution;
    fit::CageFitter fitter(programs, cage, settings);
    const render::RenderTarget image(resolution, resolution);
    const int views[] = {0};
    fitter.step(targets, views);  // compile and warm up
    fitter.render(targets.camera(0), image);
    glFinish();
    Timing t{};
    // The forward render a plain (non-differentiable) pipeline pays: stencils + tessellated raster.
    t.renderMs = bestMilliseconds(repeats, [&] {
        fitter.render(targets.camera(0), image);
        glFinish();
    });
    // As in a fit, where only a few steps per progress report measure the loss.
    t.stepMs = bestMilliseconds(repeats, [&] {
        fitter.step(targets, views, false);
        glFinish();
    });
    t.accumulateMs = bestMilliseconds(repeats, [&] {
        fitter.accumulate(targets, views, false);
        glFinish();
    });
    t.updateMs = bestMilliseconds(repeats, [&] {
        fitter.update();
        glFinish();
    });
    return t;
}

}  // namespace

int runStepCost(const StepCostOptions& o) {
    auto context = context::createHeadlessContext(o.glProvider);
    const auto info = context::currentGlInfo();
    gl::ProgramCache programs(gl::platformDefines());
    const auto reference = mesh::makeLumpySphere(5, 0.15f, 1);
    const render::MeshRenderer referenceRenderer(reference.positions, mesh::vertexNormals(reference),
                                                 {reference.faceIndices.begin(), reference.faceIndices.end()});
    std::printf("renderer: %s\n", info.renderer.c_str());

    std::vector<std::vector<std::string>> rows{{"table", "cage_faces", "parameters", "resolution", "render_ms", "step_ms", "ratio"}};
    const auto cage = mesh::makeQuadSphere(6);
    std::printf("\nstep cost, quad-sphere cage (%d faces, %d parameters), best of %d\n", cage.faceCount(),
                3 * cage.vertexCount(), o.repeats);
    std::printf("%10s %12s %12s %8s %14s %10s\n", "resolution", "render ms", "step ms", "ratio", "P+2R+G ms",
                "Adam ms");
    // The same tables as Markdown, for summaries (subdfit-bench accuracy folds this file in).
    std::string markdown = "## Step cost (" + info.renderer + ")\n\nOne SGE step over one forward render, best of " +
                           std::to_string(o.repeats) + "; quad-sphere cage of " + std::to_string(cage.faceCount()) +
                           " faces. Two renders are the floor (2.0).\n\n| resolution | render ms | step ms | ratio |\n"
                           "|---|---|---|---|\n";
    char line[160];
    double defaultRatio = 0.0;
    for (int resolution : {128, 256, 512}) {
        const auto t = timeCage(programs, cage, referenceRenderer, resolution, o.repeats);
        const double ratio = t.stepMs / t.renderMs;
        if (resolution == 256) defaultRatio = ratio;
        std::printf("%10d %12.2f %12.2f %8.2f %14.2f %10.2f\n", resolution, t.renderMs, t.stepMs, ratio,
                    t.accumulateMs, t.updateMs);
        std::snprintf(line, sizeof line, "| %d² | %.2f | %.2f | %.2f |\n", resolution, t.renderMs, t.stepMs, ratio);
        markdown += line;
        rows.push_back({"resolution", std::to_string(cage.faceCount()), std::to_string(3 * cage.vertexCount()),
                        std::to_string(resolution), std::to_string(t.renderMs), std::to_string(t.stepMs),
                        std::to_string(ratio)});
    }

    std::printf("\nscaling at 256^2: step time against parameter count\n");
    std::printf("%10s %12s %12s %12s %8s\n", "faces", "parameters", "render ms", "step ms", "ratio");
    markdown += "\nScaling at 256²:\n\n| faces | parameters | render ms | step ms | ratio |\n|---|---|---|---|---|\n";
    for (int n : {4, 8, 16, 32}) {
        const auto sphere = mesh::makeQuadSphere(n);
        const auto t = timeCage(programs, sphere, referenceRenderer, 256, o.repeats);
        std::printf("%10d %12d %12.2f %12.2f %8.2f\n", sphere.faceCount(), 3 * sphere.vertexCount(), t.renderMs,
                    t.stepMs, t.stepMs / t.renderMs);
        std::snprintf(line, sizeof line, "| %d | %d | %.2f | %.2f | %.2f |\n", sphere.faceCount(),
                      3 * sphere.vertexCount(), t.renderMs, t.stepMs, t.stepMs / t.renderMs);
        markdown += line;
        rows.push_back({"scaling", std::to_string(sphere.faceCount()), std::to_string(3 * sphere.vertexCount()),
                        "256", std::to_string(t.renderMs), std::to_string(t.stepMs),
                        std::to_string(t.stepMs / t.renderMs)});
    }
    if (!o.out.empty()) {
        std::filesystem::create_directories(o.out);
        writeCsv(o.out / "step_cost.csv", rows);
        io::writeTextAtomically(o.out / "step_cost.md", markdown);
    }
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    std::printf("step_cost_ratio=%.2f\n", defaultRatio);
    return 0;
}

}  // namespace subdfit::bench
