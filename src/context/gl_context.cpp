#include "context/gl_context.h"

#include <glad/gl.h>

#include "context/egl_context.h"
#include "context/osmesa_context.h"
#include "util/error.h"

namespace subdfit::context {
namespace {

GlContext* loadingContext = nullptr;

GLADapiproc loadProc(const char* name) { return reinterpret_cast<GLADapiproc>(loadingContext->getProcAddress(name)); }

}  // namespace

void loadGl(GlContext& context) {
    loadingContext = &context;
    const int version = gladLoadGL(loadProc);
    loadingContext = nullptr;
    if (!version) throw Error(context.providerName() + ": could not load GL entry points");
    if (GLAD_VERSION_MAJOR(version) * 10 + GLAD_VERSION_MINOR(version) < 45)
        throw Error(context.providerName() + ": GL 4.5 core needed, got " +
                    reinterpret_cast<const char*>(glGetString(GL_VERSION)));
    GLint maxPatchVertices = 0, maxTessLevel = 0, maxComputeInvocations = 0;
    glGetIntegerv(GL_MAX_PATCH_VERTICES, &maxPatchVertices);
    glGetIntegerv(GL_MAX_TESS_GEN_LEVEL, &maxTessLevel);
    glGetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &maxComputeInvocations);
    if (maxPatchVertices < 1 || maxTessLevel < 16 || maxComputeInvocations < 256)
        throw Error(context.providerName() + ": tessellation or compute support is missing");
}

std::unique_ptr<GlContext> createHeadlessContext(GlProvider provider) {
    std::unique_ptr<GlContext> context;
    switch (provider) {
        case GlProvider::Osmesa: context = createOsmesaContext(); break;
        case GlProvider::Egl: context = createEglContext(); break;
        case GlProvider::Auto: try { context = createOsmesaContext();
            } catch (const Error&) {
                context = createEglContext();
            }
            break;
    }
    loadGl(*context);
    return context;
}

GlInfo currentGlInfo() {
    GlInfo info;
    info.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    info.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    info.hasAtomicFloat = GLAD_GL_NV_shader_atomic_float != 0;
    return info;
}

}  // namespace subdfit::context
