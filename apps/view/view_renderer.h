#pragma once
// Draws one 3D view: renders the shown surface and/or the reference through the core's
// RenderTarget at the view's size, then composites the mode's picture into the window with one
// fullscreen triangle (and the cage's edges on top when asked). Knows nothing of where the
// surface comes from: a fit session, a shipped asset or a baseline's triangles.
#include <functional>
#include <memory>
#include <optional>

#include <glm/vec2.hpp>

#include "cage_wireframe.h"
#include "gl/vertex_array.h"
#include "maps/map_parameters.h"
#include "render/render_target.h"
#include "view_mode.h"

namespace subdfit::view {

struct ViewSettings {
    ViewMode mode = ViewMode::Fit;
    bool cageWireframe = false;
    float scale = 1.0f;  // the mode's colour-map gain
};

using DrawInto = std::function<void(const render::Camera&, const render::RenderTarget&)>;

// What one view shows.
struct ViewSource {
    DrawInto draw;                              // the surface shown (modes that read the fit's buffers)
    DrawInto drawReference;                     // the reference (modes that read the target's); may be empty
    const maps::MapParameters* maps = nullptr;  // the surface's maps, for the map modes
    const CageWireframe* wireframe = nullptr;   // with the cage's control vertices:
    const gl::Buffer* cageVertices = nullptr;
};

class ViewRenderer {
public:
    ViewRenderer() = default;

    // Into the default framebuffer's rectangle at `origin` (lower-left, pixels) of `size`.
    void draw(const ViewSource& source, const render::Camera& camera, const ViewSettings& settings, glm::ivec2 origin,
              glm::ivec2 size);

private:
    gl::ProgramCache programs_;  // the viewer's own, so a saved report lists only the fit's programs
    std::unique_ptr<render::RenderTarget> fit_, target_;
    std::optional<gl::VertexArray> emptyVertexArray_;  // made on the first draw, with the context current
};

}  // namespace subdfit::view
