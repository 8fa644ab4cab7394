#pragma once
// What every raster pass of subdfit starts with: its target bound and cleared, its raster state
// set whole (by default depth-tested, never culled), the camera's uniforms set.
#include "gl/program.h"
#include "gl/raster_state.h"
#include "render/camera.h"
#include "render/render_target.h"

namespace subdfit::render {

inline void beginRasterPass(const gl::Program& program, const Camera& camera, const RenderTarget& target,
                            const gl::RasterState& state = {}) {
    target.bindAndClear();
    state.apply();
    program.use();
    program.set("uViewProjection", camera.viewProjection());
    program.set("uView", camera.view);
    program.set("uEye", camera.eye);
}

}  // namespace subdfit::render
