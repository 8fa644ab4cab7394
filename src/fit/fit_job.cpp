#include "fit/fit_job.h"

#include <chrono>

#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/output_folder.h"

namespace subdfit::fit {

FitReport runFit(const FitOptions& o, const FitHooks& hooks) {
    validate(o);
    io::checkOutputFolder(o.out, {.ownMarkers = kFitResultMarkers, .force = o.force});
    const auto started = std::chrono::steady_clock::now();
    auto context = context::createHeadlessContext(o.glProvider);
    gl::ProgramCache programs(gl::platformDefines());
    FitScene scene(o, programs);
    FitRun run(o, programs, scene);
    const auto checkpoint = o.out / "checkpoint.bin";
    if (o.resume && !run.resume(checkpoint) && hooks.note)
        hooks.note("no checkpoint at " + checkpoint.string() + " to resume: starting from step 0");
    run.run(checkpoint, hooks);
    FitReport report = run.writeResults(o.out, *context);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io::writeTextAtomically(o.out / "report.json", toJson(report).dump(2) + "\n");
    return report;
}

}  // namespace subdfit::fit
