#pragma once
// What a fit spends depends on the device. On a software rasterizer (llvmpipe) a step at 256²
// costs tens of milliseconds, so the defaults stay modest; on a hardware GPU it costs well under
// a millisecond and per-step overhead, not pixels, bounds it, so the same defaults would leave it
// idle: there the options left to the device (fit_options.h, kByDevice) get more views, a finer
// resolution and more steps. Options given by the user are never changed.
#include <string>

#include "fit/fit_options.h"

namespace subdfit::fit {

struct DeviceDefaults {
    int views, resolution, steps;
};
// `steps` is a cap, not a plan: the plateau schedule ends a fit once it has converged (or, from
// a start it cannot improve on, after its probation), so the cap only has to be generous.
inline constexpr DeviceDefaults kSoftwareDefaults{.views = 24, .resolution = 256, .steps = 4000};
inline constexpr DeviceDefaults kGpuDefaults{.views = 48, .resolution = 512, .steps = 20000};

// True unless GL_RENDERER names a software rasterizer (llvmpipe, softpipe, swrast, ...).
bool isHardwareRenderer(const std::string& renderer);

// Fills the options still kByDevice from the device's defaults. Returns one line for the user
// saying what the device is and what was chosen ("" when every option was given).
std::string resolveDeviceDefaults(FitOptions& options, const std::string& renderer);

// The same for the current GL context's renderer.
std::string resolveForCurrentDevice(FitOptions& options);

}  // namespace subdfit::fit
