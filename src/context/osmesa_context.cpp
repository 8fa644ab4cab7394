#include "context/osmesa_context.h"

#include <GL/osmesa.h>

#include <vector>

#include "util/error.h"

namespace subdfit::context {
namespace {

class OsmesaContext final : public GlContext {
public:
    OsmesaContext() {
        const int attribs[] = {OSMESA_FORMAT,
                               OSMESA_RGBA,
                               OSMESA_DEPTH_BITS,
                               24,
                               OSMESA_PROFILE,
                               OSMESA_CORE_PROFILE,
                               OSMESA_CONTEXT_MAJOR_VERSION,
                               4,
                               OSMESA_CONTEXT_MINOR_VERSION,
                               5,
                               0};
        context_ = OSMesaCreateContextAttribs(attribs, nullptr);
        if (!context_) throw Error("OSMesa: could not create a GL 4.5 core context");
        makeCurrent();
    }
    ~OsmesaContext() override { OSMesaDestroyContext(context_); }

    void makeCurrent() override {
        // OSMesa insists on a colour buffer; a 1x1 one is enough, all real work goes to FBOs.
        if (!OSMesaMakeCurrent(context_, pixel_.data(), GL_UNSIGNED_BYTE, 1, 1))
            throw Error("OSMesa: OSMesaMakeCurrent failed");
    }
    GlProc getProcAddress(const char* name) override { return reinterpret_cast<GlProc>(OSMesaGetProcAddress(name)); }
    std::string providerName() const override { return "osmesa"; }

private:
    OSMesaContext context_ = nullptr;
    std::vector<unsigned char> pixel_ = std::vector<unsigned char>(4);
};

}  // namespace

std::unique_ptr<GlContext> createOsmesaContext() { return std::make_unique<OsmesaContext>(); }

}  // namespace subdfit::context
