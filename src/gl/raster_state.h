#pragma once
// The fixed-function state of one raster pass, set whole before it draws, so that no pass
// inherits what the previous one left behind. Faces are never culled: open surfaces are seen
// from both sides, and fitted windings are not to be trusted mid-fit.
#include <glad/gl.h>

namespace subdfit::gl {

struct RasterState {
    bool depthTest = true;
    bool depthClamp = false;  // keep geometry past the near/far planes (drifting soups)
    bool alphaBlend = false;  // source-alpha over what is there (overlays)

    void apply() const {
        glDisable(GL_CULL_FACE);
        depthTest ? glEnable(GL_DEPTH_TEST) : glDisable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        depthClamp ? glEnable(GL_DEPTH_CLAMP) : glDisable(GL_DEPTH_CLAMP);
        if (alphaBlend) {
            glEnable(GL_BLEND);
            glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        } else {
            glDisable(GL_BLEND);
        }
    }
};

}  // namespace subdfit::gl
