#pragma once
// One interface for every way subdfit gets a GL 4.5 core context: OSMesa (CPU, offscreen, the
// default), EGL (headless, on a GPU driver or Mesa's surfaceless platform) and, in the viewer
// only, GLFW. The core renders into FBOs it owns, so a context never needs a default framebuffer.
#include <memory>
#include <string>

#include "util/named_enum.h"

namespace subdfit::context {

using GlProc = void (*)();

class GlContext {
public:
    virtual ~GlContext() = default;
    virtual void makeCurrent() = 0;
    virtual GlProc getProcAddress(const char* name) = 0;
    virtual std::string providerName() const = 0;
};

// Where a headless context comes from; Auto: OSMesa, else EGL.
enum class GlProvider { Auto, Osmesa, Egl };

// Creates a context from `provider`, makes it current, loads GL through it and checks that it
// has what subdfit needs (4.5 core, tessellation, compute). Throws subdfit::Error with a clear
// message otherwise.
std::unique_ptr<GlContext> createHeadlessContext(GlProvider provider = GlProvider::Auto);

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

template <>
struct subdfit::EnumNames<subdfit::context::GlProvider> {
    using P = context::GlProvider;
    static constexpr std::array names{std::pair{P::Auto, std::string_view("auto")},
                                      std::pair{P::Osmesa, std::string_view("osmesa")},
                                      std::pair{P::Egl, std::string_view("egl")}};
};
