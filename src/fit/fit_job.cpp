#include "fit/fit_job.h"

#include <chrono>

#include "fit/device_defaults.h"
#include "gl/platform_defines.h"
#include "io/atomic_file.h"
#include "io/output_folder.h"
#include "util/json_text.h"

namespace subdfit::fit {

FitReport runFit(const FitOptions& options, const FitHooks& hooks) {
    validate(options);
    // The atlas coordinates come from the bake onto the reference, which only simplify runs.
    if (options.appearanceAtlas != 0) throw OptionError("appearance_atlas", "applies to simplify only");
    io::checkOutputFolder(options.out, {.ownMarkers = kFitResultMarkers, .force = options.force});
    const auto started = std::chrono::steady_clock::now();
    auto context = context::createHeadlessContext(options.glProvider);
    FitOptions o = options;
    const std::string chosen = resolveForCurrentDevice(o);
    gl::ProgramCache programs(gl::platformDefines());
    const ResolvedFitOptions checked = resolved(o);
    FitScene scene(checked, programs);
    FitRun run(checked, programs, scene);
    if (!chosen.empty() && hooks.note) hooks.note(chosen);  // once the inputs have loaded: a bad one gets one line
    const auto checkpoint = o.out / "checkpoint.bin";
    if (o.resume && !run.resume(checkpoint) && hooks.note)
        hooks.note("no checkpoint at " + checkpoint.string() + " to resume: starting from step 0");
    run.run(checkpoint, hooks);
    FitReport report = run.writeResults(o.out, *context);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    io::writeTextAtomically(o.out / "report.json", jsonText(toJson(report), 2));
    return report;
}

}  // namespace subdfit::fit
