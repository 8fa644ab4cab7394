#pragma once
// One interface for every way subdfit gets a GL 4.5 core context: OSMesa (CPU, offscreen, the
// default), EGL (headless, on a GPU driver or Mesa's surfaceless platform) and, in the viewer
// only, GLFW. The core renders into FBOs it owns, so a context never needs a default framebuffer.
#include <memory>
#include <string>

namespace subdfit::context {

using GlProc = void (*)();

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual void makeCurrent() = 0;
    virtual GlProc getProcAddress(const char* name) = 0;
    virtual std::string providerName() const = 0;
};

// Creates a context by provider name ("osmesa", "egl", or "auto": OSMesa, else EGL), makes it
// current, loads GL through it and checks that it has what subdfit needs (4.5 core,
// tessellation, compute). Throws subdfit::Error with a clear message otherwise.
std::unique_ptr<GlContext> createHeadlessContext(const std::string& provider = "auto");

// The names createHeadlessContext takes, as every command's --gl help says them.
inline constexpr const char* kGlProviderHelp = "GL provider: auto, osmesa, egl";

// Loads GL entry points through `context` and checks version and limits. Used by every
// provider, the viewer's GLFW one included.
void loadGl(GlContext& context);

// Facts about the current context, for reports and logs.
struct GlInfo {
    std::string renderer, version;
    bool hasAtomicFloat = false;
};
GlInfo currentGlInfo();

}  // namespace subdfit::context
