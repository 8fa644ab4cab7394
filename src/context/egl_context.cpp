#include "context/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "util/error.h"

namespace subdfit::context {
namespace {

EGLDisplay pickDisplay() {
    auto getPlatformDisplay =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
    auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    if (getPlatformDisplay && queryDevices) {
        EGLDeviceEXT devices[16];
        EGLint count = 0;
        if (queryDevices(16, devices, &count) && count > 0)
            return getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[0], nullptr);
    }
    if (getPlatformDisplay) return getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

class EglContext final : public GlContext {
public:
    EglContext() {
        display_ = pickDisplay();
        if (display_ == EGL_NO_DISPLAY) throw Error("EGL: no display");
        if (!eglInitialize(display_, nullptr, nullptr)) throw Error("EGL: eglInitialize failed");
        if (!eglBindAPI(EGL_OPENGL_API)) throw Error("EGL: desktop OpenGL API not available");
        const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                        EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        eglChooseConfig(display_, configAttribs, &config, 1, &configCount);
        const EGLint contextAttribs[] = {
            EGL_CONTEXT_MAJOR_VERSION,           4,       EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
            EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        context_ = eglCreateContext(display_, configCount ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, contextAttribs);
        if (context_ == EGL_NO_CONTEXT) {
            eglTerminate(display_);
            throw Error("EGL: could not create a GL 4.5 core context");
        }
        makeCurrent();
    }
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    void makeCurrent() override {
        if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
            throw Error("EGL: eglMakeCurrent (surfaceless) failed");
    }
    GlProc getProcAddress(const char* name) override { return reinterpret_cast<GlProc>(eglGetProcAddress(name)); }
    std::string providerName() const override { return "egl"; }

private:
    EGLDisplay display_ = EGL_NO_DISPLAY;
    EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext() { return std::make_unique<EglContext>(); }

}  // namespace subdfit::context
