#pragma once
// What every raster pass of subdfit starts with: its target bound and cleared, depth test on,
// no culling (open surfaces are seen from both sides), the camera's uniforms set.
#include "gl/program.h"
#include "render/camera.h"
#include "render/render_target.h"

namespace subdfit::render {

inline void beginRasterPass(const gl::Program& program, const Camera& camera, const RenderTarget& target) {
    target.bindAndClear();
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    program.use();
    program.set("uViewProjection", camera.viewProjection());
    program.set("uView", camera.view);
    program.set("uEye", camera.eye);
}

}  // namespace subdfit::render
