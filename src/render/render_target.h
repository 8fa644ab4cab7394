#pragma once
// What one raster pass writes: shaded colour (float, so that ε-small differences survive),
// the ptex face id (−1 on background) and the patch-local (u,v), plus depth.
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <vector>

#include "gl/framebuffer.h"
#include "gl/texture.h"

namespace subdfit::render {

// Which attachments a target has, and where it keeps the face id.
struct TargetLayout {
    // The (u, v) attachment, for passes whose readers need it (a texel group's turn): without
    // it, it is not made, cleared or written.
    bool patchUv = true;
    // The face id as the colour's alpha (a float, exact below 2^24) instead of an integer
    // attachment of its own: what the SGE passes draw into, so that G reads a pixel's colour and
    // face in one fetch and the renders write one target fewer. Reads still return alpha as
    // coverage (1 on the surface, 0 on background) and the face ids apart.
    bool faceInAlpha = false;
};

class RenderTarget {
public:
    RenderTarget(int width, int height, TargetLayout layout = {});

    void bindAndClear() const;  // binds the FBO, sets the viewport, clears to background
    int width() const { return width_; }
    int height() const { return height_; }
    bool faceInAlpha() const { return layout_.faceInAlpha; }

    const gl::Texture& color() const { return color_; }
    const gl::Texture& faceId() const;  // only a target without faceInAlpha
    const gl::Texture& patchUv() const;

    std::vector<glm::vec4> readColor() const;
    std::vector<int> readFaceId() const;
    std::vector<glm::vec2> readPatchUv() const;
    std::vector<float> readDepth() const;  // window depth in [0, 1], 1 on background

private:
    std::vector<glm::vec4> readColorAttachment() const;

    int width_, height_;
    TargetLayout layout_;
    gl::Texture color_, faceId_, patchUv_, depth_;
    gl::Framebuffer framebuffer_;
};

}  // namespace subdfit::render
