#pragma once
// What every raster pass of subdfit starts with: its target bound and cleared, its raster state
// set whole (by default depth-tested, never culled), the camera's uniforms set.
#include "gl/program.h"
#include "gl/raster_state.h"
#include "render/camera.h"
#include "render/render_target.h"

namespace subdfit::render {

// The program in use with the camera's uniforms (a pass of several draws switches programs).
inline void useWithCamera(const gl::Program& program, const Camera& camera) {
    program.use();
    program.set("uViewProjection", camera.viewProjection());
    program.set("uView", camera.view);
    program.set("uEye", camera.eye);
}

inline void beginRasterPass(const RenderTarget& target, const gl::RasterState& state = {}) {
    target.bindAndClear();
    state.apply();
}

inline void beginRasterPass(const gl::Program& program, const Camera& camera, const RenderTarget& target,
                            const gl::RasterState& state = {}) {
    beginRasterPass(target, state);
    useWithCamera(program, camera);
}

}  // namespace subdfit::render
