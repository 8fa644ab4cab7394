#include "fit/device_defaults.h"

#include <algorithm>
#include <cctype>

#include "context/gl_context.h"

namespace subdfit::fit {

bool isHardwareRenderer(const std::string& renderer) {
    std::string lower = renderer;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    for (const char* software : {"llvmpipe", "softpipe", "swrast", "software", "swiftshader", "lavapipe"})
        if (lower.find(software) != std::string::npos) return false;
    return true;
}

std::string resolveDeviceDefaults(FitOptions& o, const std::string& renderer) {
    const bool hardware = isHardwareRenderer(renderer);
    const DeviceDefaults& d = hardware ? kGpuDefaults : kSoftwareDefaults;
    bool chose = false;
    for (auto [field, value] : {std::pair{&o.views, d.views}, {&o.resolution, d.resolution}, {&o.steps, d.steps}}) {
        if (*field != kByDevice) continue;
        *field = value;
        chose = true;
    }
    if (!chose) return "";
    return renderer + (hardware ? " (GPU)" : " (software)") + ": " + std::to_string(o.views) + " views at " +
           std::to_string(o.resolution) + "², at most " + std::to_string(o.steps) + " steps" +
           (o.schedule == Schedule::Plateau ? " (it stops once converged)" : "") +
           (hardware ? " (--views, --res, --steps override)" : "");
}

std::string resolveForCurrentDevice(FitOptions& o) {
    return resolveDeviceDefaults(o, context::currentGlInfo().renderer);
}

}  // namespace subdfit::fit
