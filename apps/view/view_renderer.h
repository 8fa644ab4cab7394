#pragma once
// Draws the 3D view of a fit session: renders the fit and/or the reference through the core's
// RenderTarget at the view's size, then composites the mode's picture into the window with one
// fullscreen triangle (and the cage's edges on top when asked).
#include <memory>
#include <optional>

#include <glm/vec2.hpp>

#include "cage_wireframe.h"
#include "gl/vertex_array.h"
#include "fit_session.h"
#include "view_mode.h"

namespace subdfit::view {

struct ViewSettings {
    ViewMode mode = ViewMode::Fit;
    bool cageWireframe = false;
    float scale = 1.0f;  // the mode's colour-map gain
};

class ViewRenderer {
public:
    ViewRenderer() = default;

    // Into the default framebuffer's rectangle at `origin` (lower-left, pixels) of `size`.
    void draw(FitSession& session, const CageWireframe& wireframe, const render::Camera& camera,
              const ViewSettings& settings, glm::ivec2 origin, glm::ivec2 size);

private:
    gl::ProgramCache programs_;  // the viewer's own, so a saved report lists only the fit's programs
    std::unique_ptr<render::RenderTarget> fit_, target_;
    std::optional<gl::VertexArray> emptyVertexArray_;  // made on the first draw, with the context current
};

}  // namespace subdfit::view
