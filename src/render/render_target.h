#pragma once
// What one raster pass writes: shaded colour (float, so that ε-small differences survive),
// the ptex face id (−1 on background) and the patch-local (u,v), plus depth.
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "gl/framebuffer.h"
#include "gl/texture.h"

namespace subdfit::render {

class RenderTarget {
public:
    // Without `patchUv`, for passes whose readers never need (u, v) (a fit without maps): that
    // attachment is not made, cleared or written.
    RenderTarget(int width, int height, bool patchUv = true);

    void bindAndClear() const;  // binds the FBO, sets the viewport, clears to background
    int width() const { return width_; }
    int height() const { return height_; }

    const gl::Texture& color() const { return color_; }
    const gl::Texture& faceId() const { return faceId_; }
    const gl::Texture& patchUv() const;

    std::vector<glm::vec4> readColor() const;
    std::vector<int> readFaceId() const;
    std::vector<glm::vec2> readPatchUv() const;
    std::vector<float> readDepth() const;  // window depth in [0, 1], 1 on background

private:
    int width_, height_;
    gl::Texture color_, faceId_, patchUv_, depth_;
    gl::Framebuffer framebuffer_;
};

}  // namespace subdfit::render
