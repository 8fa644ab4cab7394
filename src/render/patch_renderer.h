#pragma once
// Draws a cage's limit surface with GPU tessellation: one GL patch per OpenSubdiv patch, whose
// control points come from an SSBO of evaluated points. Writes colour, ptex face id and (u,v).
#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "maps/map_parameters.h"
#include "render/camera.h"
#include "render/render_target.h"
#include "subdiv/patch_set.h"

namespace subdfit::render {

class PatchRenderer {
public:
    // `tessLevel`: segments per base-face edge, raised to a power of two that keeps adaptive
    // patches of every depth crack-free (callers with maps ask for at least the map resolution,
    // so that the detail of the maps is actually rasterised).
    PatchRenderer(const subdiv::PatchSet& patches, int tessLevel);

    int tessLevel() const { return tessLevel_; }
    int patchCount() const { return patchCount_; }

    // With `maps`, the variant with their effects, reading `version` of the perturbed map group
    // (if any) and the current θ of the others.
    void draw(gl::ProgramCache& programs, const gl::Buffer& points, const Camera& camera, const RenderTarget& target,
              const maps::MapParameters* maps = nullptr,
              maps::ParameterVersion version = maps::ParameterVersion::Current,
              const sge::ParameterGroup* perturbed = nullptr) const;

private:
    int patchCount_, tessLevel_;
    gl::Buffer patchInfo_, patchCvs_;
    gl::GlHandle<gl::VertexArrayTraits> vertexArray_;
};

// The smallest power of two >= max(requested, 2^maxPatchDepth), capped at the GL limit of 64.
int crackFreeTessLevel(int requested, int maxPatchDepth);

}  // namespace subdfit::render
