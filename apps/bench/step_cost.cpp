// `subdfit-bench step-cost`: one SGE step's time over one forward render's time, measured in the
// same run (two renders are the floor, so the goal is <= 2.2), at a few resolutions; what a step
// asks of the GL besides its renders (dispatches, barriers, clears, synchronisations, program
// switches: the fixed costs that bound a fast GPU), counted per step; and how the step time
// scales with the number of parameters.
#include <glad/gl.h>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <functional>
#include <utility>

#include "bench_commands.h"
#include "bench_common.h"
#include "context/gl_context.h"
#include "fit/cage_fitter.h"
#include "fit/fit_run.h"
#include "gl/platform_defines.h"
#include "gl/timestamp_log.h"
#include "gl_call_counter.h"
#include "interleaved_timing.h"
#include "io/atomic_file.h"
#include "mesh/mesh_loader.h"
#include "mesh/procedural.h"
#include "render/mesh_renderer.h"

namespace subdfit::bench {
namespace {

// One scene's timings over interleaved rounds (forward render, step, step in halves, two forward
// renders): medians in ms, and the step / render ratio taken within each round.
struct Timing {
    double renderMs, stepMs;
    double accumulateMs, updateMs;  // the step's halves: P + 2R + G, then preconditioner + Adam
    Spread ratio, cpuRatio;         // wall time, and the process's CPU time (llvmpipe's threads count in)
    Spread floorCpuRatio;           // two forward renders over one, by CPU time: the bench's own check (2.0)
    // GPU timestamps (medians of their own rounds, ms): the forward render, and a step phase by phase.
    double forwardGpuMs;
    std::vector<std::pair<std::string, double>> stepPhases;
};

// Medians of a TimestampLog's phases over `rounds` runs of `pass` (already warmed up).
std::vector<std::pair<std::string, double>> gpuPhaseMedians(int rounds, gl::PhaseClock clock,
                                                            const std::function<void(gl::TimestampLog&)>& pass) {
    gl::TimestampLog log(clock);
    for (int r = 0; r < rounds; ++r) {
        log.begin();
        pass(log);
        glFinish();
    }
    std::vector<std::pair<std::string, double>> medians;
    for (const auto& [phase, ms] : log.collect()) medians.push_back({phase, spreadOf(ms).median});
    return medians;
}

// What a plain pipeline's forward render writes: colour and depth, the layout of the step's
// renders (which add the face id as alpha).
constexpr render::TargetLayout kPlainTarget{.patchUv = false, .faceInAlpha = true};

// The views of the step-cost scene: one per step, as in a fit.
const int kViews[] = {0};

Timing timeCage(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const render::MeshRenderer& reference,
                int resolution, int rounds, gl::PhaseClock clock) {
    const scene::TargetSet targets(programs, reference, render::orbitCameras(8, 1), resolution);
    fit::CageFitSettings settings;
    settings.resolution = resolution;
    fit::CageFitter fitter(programs, cage, settings);
    const render::RenderTarget image(resolution, resolution, kPlainTarget);
    const render::RenderTarget secondImage(resolution, resolution, kPlainTarget);
    fitter.step(targets, kViews);  // compile and warm up
    fitter.render(targets.camera(0), image);
    glFinish();
    std::vector<double> accumulateMs;
    const std::function<void()> workloads[] = {
        // The forward render a plain (non-differentiable) pipeline pays: stencils, the surface
        // evaluated, its triangles rasterised.
        [&] {
            fitter.forgetDrawnSurface();
            fitter.render(targets.camera(0), image);
            glFinish();
        },
        // As in a fit, where only a few steps per progress report measure the loss.
        [&] {
            fitter.step(targets, kViews, false);
            glFinish();
        },
        [&] {
            const auto start = std::chrono::steady_clock::now();
            fitter.accumulate(targets, kViews, false);
            glFinish();
            accumulateMs.push_back(
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
            fitter.update();
            glFinish();
        },
        // The floor: what two forward renders cost where the step's two stand.
        [&] {
            for (const auto* target : {&image, &secondImage}) {
                fitter.forgetDrawnSurface();
                fitter.render(targets.camera(0), *target);
            }
            glFinish();
        }};
    const auto samples = timeInterleaved(rounds, workloads);
    const double forwardGpuMs = gpuPhaseMedians(rounds, clock,
                                                [&](gl::TimestampLog& log) {
                                                    fitter.forgetDrawnSurface();
                                                    fitter.render(targets.camera(0), image);
                                                    log.mark("forward render");
                                                })
                                    .at(0)
                                    .second;
    auto stepPhases = gpuPhaseMedians(rounds, clock, [&](gl::TimestampLog& log) {
        fitter.setTimestampLog(&log);
        fitter.step(targets, kViews, false);
        fitter.setTimestampLog(nullptr);
    });
    const auto& render = samples[0];
    const auto& step = samples[1];
    std::vector<double> updateMs;
    for (size_t k = 0; k < accumulateMs.size(); ++k) updateMs.push_back(samples[2].wallMs[k] - accumulateMs[k]);
    return {spreadOf(render.wallMs).median,
            spreadOf(step.wallMs).median,
            spreadOf(accumulateMs).median,
            spreadOf(updateMs).median,
            spreadOf(perRoundRatios(step.wallMs, render.wallMs)),
            spreadOf(perRoundRatios(step.cpuMs, render.cpuMs)),
            spreadOf(perRoundRatios(samples[3].cpuMs, render.cpuMs)),
            forwardGpuMs,
            std::move(stepPhases)};
}

struct CountedPass {
    std::string name;
    GlCallCounts counts;
    double perSteps = 1.0;  // the counts are over this many steps
};

// The GL calls of one forward render and of one step of each kind (a vertex turn, a texel turn),
// warmed up first so that no compilation is counted.
std::vector<CountedPass> countSteps(gl::ProgramCache& programs, const mesh::PolygonMesh& cage,
                                    const render::MeshRenderer& reference) {
    constexpr int kResolution = 128;  // the counts do not depend on it
    const scene::TargetSet targets(programs, reference, render::orbitCameras(8, 1), kResolution);
    const render::RenderTarget image(kResolution, kResolution, kPlainTarget);
    std::vector<CountedPass> passes;

    fit::CageFitSettings settings;
    settings.resolution = kResolution;
    fit::CageFitter fitter(programs, cage, settings);
    fitter.step(targets, kViews, false);
    fitter.render(targets.camera(0), image);
    glFinish();
    {
        GlCallCounter counter;
        fitter.forgetDrawnSurface();
        fitter.render(targets.camera(0), image);
        passes.push_back({"forward render", counter.take()});
        fitter.step(targets, kViews, false);
        passes.push_back({"step, vertex turn", counter.take()});
        fitter.step(targets, kViews, true);
        passes.push_back({"step measuring the loss", counter.take()});
        fitter.takeMeanLoss();
        passes.push_back({"loss readback (per report)", counter.take()});
    }

    // With displacement and normal maps, from the first step: turns alternate vertices / a map.
    settings.mapEffects = {maps::MapKind::Displacement, maps::MapKind::NormalMap};
    fit::CageFitter mapped(programs, cage, settings);
    for (int warm = 0; warm < 4; ++warm) mapped.step(targets, kViews, false);
    glFinish();
    {
        GlCallCounter counter;
        mapped.step(targets, kViews, false);
        passes.push_back({"maps scene, vertex turn", counter.take()});
        mapped.step(targets, kViews, false);
        passes.push_back({"maps scene, texel turn", counter.take()});
    }
    return passes;
}

// Per step of a fit as `subdfit fit` runs it (views taking turns, loss for progress, the plateau
// schedule's monitor renders and checkpoints), averaged over its first steps.
CountedPass countFitLoop(gl::ProgramCache& programs, const mesh::PolygonMesh& cage, const mesh::PolygonMesh& reference,
                         const std::filesystem::path& scratch) {
    fit::FitOptions options;
    options.views = 8;
    options.resolution = 128;
    options.steps = 500;
    options.out = scratch;
    fit::FitScene scene(fit::resolved(options), programs, cage, reference);
    fit::FitRun run(fit::resolved(options), programs, scene);
    constexpr int kSteps = 60;
    run.runTo(5, scratch / "checkpoint.bin");  // compile and warm up
    GlCallCounter counter;
    run.runTo(5 + kSteps, scratch / "checkpoint.bin");
    return {"fit loop (mean per step)", counter.take(), double(kSteps)};
}

const gl::ProgramSpec kEmptyPass{"empty_pass", {{GL_COMPUTE_SHADER, "empty_pass.comp"}}};

// What a dispatch and the barrier after it cost by themselves: an empty one-group pass, `count` in
// a row, per pass (µs, wall and the process's CPU time). On llvmpipe most of it is handing the
// work to its threads and waiting for them, whatever the work.
std::pair<double, double> emptyDispatchMicroseconds(gl::ProgramCache& programs, int count) {
    const auto& program = programs.get(kEmptyPass);
    program.use();
    const gl::Buffer counter(sizeof(std::uint32_t));
    counter.bindStorage(0);
    glFinish();
    const auto wallStart = std::chrono::steady_clock::now();
    const double cpuStart = processCpuSeconds();
    for (int k = 0; k < count; ++k) {
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    glFinish();
    const double wallUs =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - wallStart).count();
    return {wallUs / count, 1e6 * (processCpuSeconds() - cpuStart) / count};
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
    // A software rasterizer's timestamps land at its next flush, not at the phase's end.
    const bool software =
        info.renderer.find("llvmpipe") != std::string::npos || info.renderer.find("softpipe") != std::string::npos;
    const gl::PhaseClock phaseClock = software ? gl::PhaseClock::HostAfterFinish : gl::PhaseClock::GpuTimestamp;

    std::vector<std::vector<std::string>> rows{
        {"table", "cage_faces", "parameters", "resolution", "render_ms", "step_ms", "ratio", "ratio_q1", "ratio_q3",
         "ratio_ci_low", "ratio_ci_high", "cpu_ratio", "cpu_ratio_q1", "cpu_ratio_q3", "two_renders_cpu_ratio"}};
    auto addRow = [&](const char* table, const mesh::PolygonMesh& mesh, int resolution, const Timing& t) {
        std::vector<std::string> row{table, std::to_string(mesh.faceCount()), std::to_string(3 * mesh.vertexCount()),
                                     std::to_string(resolution)};
        for (double value : {t.renderMs, t.stepMs, t.ratio.median, t.ratio.q1, t.ratio.q3, t.ratio.low, t.ratio.high,
                             t.cpuRatio.median, t.cpuRatio.q1, t.cpuRatio.q3, t.floorCpuRatio.median})
            row.push_back(std::to_string(value));
        rows.push_back(row);
    };
    const auto cage = mesh::makeQuadSphere(6);
    std::printf(
        "\nstep cost, quad-sphere cage (%d faces, %d parameters), %d interleaved rounds: medians, the ratio\n"
        "per round with its quartiles and the median's 95%% interval; CPU: the process's CPU time\n",
        cage.faceCount(), 3 * cage.vertexCount(), o.repeats);
    std::printf("%10s %10s %10s %6s %11s %11s %10s %11s %10s %9s %9s\n", "resolution", "render ms", "step ms", "ratio",
                "quartiles", "95% median", "CPU ratio", "quartiles", "P+2R+G ms", "update ms", "2R CPU");
    // The same tables as Markdown, for summaries (subdfit-bench accuracy folds this file in).
    std::string markdown = "## Step cost (" + info.renderer + ")\n\nOne SGE step over one forward render, " +
                           std::to_string(o.repeats) +
                           " interleaved rounds (medians; the ratio per round, with its quartiles and the median's "
                           "95 % interval; CPU: the process's CPU time); quad-sphere cage of " +
                           std::to_string(cage.faceCount()) +
                           " faces. Two renders are the floor (2.0).\n\n| resolution | render ms | step ms | ratio | "
                           "quartiles | median's 95 % | CPU ratio |\n|---|---|---|---|---|---|---|\n";
    char line[320];
    std::vector<Timing> resolutionTimings;
    for (int resolution : o.resolutions) {
        const auto& t = resolutionTimings.emplace_back(
            timeCage(programs, cage, referenceRenderer, resolution, o.repeats, phaseClock));
        std::printf("%10d %10.2f %10.2f %6.2f %5.2f-%5.2f %5.2f-%5.2f %10.2f %5.2f-%5.2f %10.2f %9.2f %9.2f\n",
                    resolution, t.renderMs, t.stepMs, t.ratio.median, t.ratio.q1, t.ratio.q3, t.ratio.low, t.ratio.high,
                    t.cpuRatio.median, t.cpuRatio.q1, t.cpuRatio.q3, t.accumulateMs, t.updateMs,
                    t.floorCpuRatio.median);
        std::snprintf(line, sizeof line, "| %d² | %.2f | %.2f | %.2f | %.2f-%.2f | %.2f-%.2f | %.2f (%.2f-%.2f) |\n",
                      resolution, t.renderMs, t.stepMs, t.ratio.median, t.ratio.q1, t.ratio.q3, t.ratio.low,
                      t.ratio.high, t.cpuRatio.median, t.cpuRatio.q1, t.cpuRatio.q3);
        markdown += line;
        addRow("resolution", cage, resolution, t);
        std::printf("step_cost_ratio_%d=%.2f\nstep_cost_ratio_quartiles_%d=%.2f-%.2f\nstep_cost_cpu_ratio_%d=%.2f\n",
                    resolution, t.ratio.median, resolution, t.ratio.q1, t.ratio.q3, resolution, t.cpuRatio.median);
    }

    // What the GL is asked per step: calls, not time, so the figures hold on any device.
    auto passes = countSteps(programs, cage, referenceRenderer);
    {
        // The fit loop's checkpoints go to a folder of their own, removed after.
        const auto scratch = std::filesystem::temp_directory_path() / ("subdfit-step-cost-" + std::to_string(getpid()));
        passes.push_back(countFitLoop(programs, cage, reference, scratch));
        std::filesystem::remove_all(scratch);
    }
    // Where a step's GPU time goes: a phase's time includes the wait for the phase before it
    // (barriers), and the step's wall time beyond their sum is the CPU's and the driver's.
    const char* clockName = software ? "the host's clock after glFinish each phase" : "GPU timestamps";
    std::printf("\nTime by phase (%s, median ms; the step's wall time beside)\n", clockName);
    markdown += std::string("\nTime by phase (") + clockName + ", median ms):\n\n";
    for (size_t k = 0; k < o.resolutions.size(); ++k) {
        const Timing& t = resolutionTimings[k];
        double stepSum = 0.0;
        std::snprintf(line, sizeof line, "forward render %.3f, ", t.forwardGpuMs);
        std::string cells = line;
        for (const auto& [phase, ms] : t.stepPhases) {
            stepSum += ms;
            std::snprintf(line, sizeof line, "%s %.3f, ", phase.c_str(), ms);
            cells += line;
        }
        std::snprintf(line, sizeof line, "phases' sum %.3f, step wall %.3f", stepSum, t.stepMs);
        cells += line;
        std::printf("%5d²: %s\n", o.resolutions[k], cells.c_str());
        markdown += "- " + std::to_string(o.resolutions[k]) + "²: " + cells + "\n";
    }

    const auto names = GlCallCounts::names();
    std::printf("\nGL calls per step (quad-sphere cage, one view per step)\n%-28s", "");
    markdown += "\nGL calls per step (one view per step):\n\n| |";
    for (const auto& name : names) {
        std::printf(" %9.9s", name.c_str());
        markdown += " " + name + " |";
    }
    markdown += "\n|---|" + [&] {
        std::string cells;
        for (size_t k = 0; k < names.size(); ++k) cells += "---|";
        return cells;
    }() + "\n";
    std::printf("\n");
    std::vector<std::vector<std::string>> countRows{{"pass"}};
    countRows.front().insert(countRows.front().end(), names.begin(), names.end());
    for (const auto& pass : passes) {
        std::printf("%-28s", pass.name.c_str());
        markdown += "| " + pass.name + " |";
        countRows.push_back({pass.name});
        for (long value : pass.counts.values()) {
            const double perStep = double(value) / pass.perSteps;
            std::snprintf(line, sizeof line, pass.perSteps == 1.0 ? "%.0f" : "%.1f", perStep);
            std::printf(" %9s", line);
            markdown += std::string(" ") + line + " |";
            countRows.back().push_back(line);
        }
        std::printf("\n");
        markdown += "\n";
    }

    // The counts priced: a vertex turn's dispatches at what one costs by itself, against the step.
    {
        emptyDispatchMicroseconds(programs, 20);  // compile and warm up
        const auto [wallUs, cpuUs] = emptyDispatchMicroseconds(programs, 1000);
        const double dispatches = double(passes.at(1).counts.dispatches);  // "step, vertex turn"
        std::printf(
            "\na dispatch and its barrier by themselves (an empty pass, 1000 in a row): %.1f us wall, %.1f us CPU;\n"
            "a vertex turn's %.0f: %.2f ms wall",
            wallUs, cpuUs, dispatches, dispatches * wallUs / 1000.0);
        for (size_t k = 0; k < o.resolutions.size(); ++k)
            std::printf(", %.0f %% of its step at %d²",
                        100.0 * dispatches * wallUs / 1000.0 / resolutionTimings[k].stepMs, o.resolutions[k]);
        std::printf("\ndispatch_us=%.1f\ndispatch_cpu_us=%.1f\n", wallUs, cpuUs);
        std::snprintf(
            line, sizeof line,
            "\nA dispatch and its barrier by themselves (an empty pass, 1000 in a row): %.1f µs wall, %.1f µs "
            "CPU.\n",
            wallUs, cpuUs);
        markdown += line;
    }

    // Fewer rounds: the larger cages' renders take longer, and only the trend matters here.
    const int scalingRounds = std::max(5, o.repeats / 4);
    std::printf("\nscaling at 256^2: step time against parameter count (%d rounds)\n", scalingRounds);
    std::printf("%10s %12s %12s %12s %8s %11s\n", "faces", "parameters", "render ms", "step ms", "ratio", "quartiles");
    markdown += "\nScaling at 256²:\n\n| faces | parameters | render ms | step ms | ratio |\n|---|---|---|---|---|\n";
    for (int n : o.scaling ? std::vector<int>{4, 8, 16, 32} : std::vector<int>{}) {
        const auto sphere = mesh::makeQuadSphere(n);
        const auto t = timeCage(programs, sphere, referenceRenderer, 256, scalingRounds, phaseClock);
        std::printf("%10d %12d %12.2f %12.2f %8.2f %5.2f-%5.2f\n", sphere.faceCount(), 3 * sphere.vertexCount(),
                    t.renderMs, t.stepMs, t.ratio.median, t.ratio.q1, t.ratio.q3);
        std::snprintf(line, sizeof line, "| %d | %d | %.2f | %.2f | %.2f |\n", sphere.faceCount(),
                      3 * sphere.vertexCount(), t.renderMs, t.stepMs, t.ratio.median);
        markdown += line;
        addRow("scaling", sphere, 256, t);
    }
    if (!o.out.empty()) {
        std::filesystem::create_directories(o.out);
        writeCsv(o.out / "step_cost.csv", rows);
        writeCsv(o.out / "step_calls.csv", countRows);
        io::writeTextAtomically(o.out / "step_cost.md", markdown);
    }
    std::printf("peak_rss_mib=%.0f\n", peakResidentMiB());
    return 0;
}

}  // namespace subdfit::bench
