#pragma once
// The cage's edges drawn over the view, straight from the control vertices on the GPU (the
// fitter's θ: no readback per frame), its OpenSubdiv tags in colour: infinitely sharp creases,
// semi-sharp ones, and corner vertices as dots.
#include <glm/vec4.hpp>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/vertex_array.h"
#include "mesh/polygon_mesh.h"
#include "render/camera.h"

namespace subdfit::view {

// The colours, for the panel's legend too.
inline constexpr glm::vec4 kSmoothEdgeColor{1.0f, 0.85f, 0.25f, 0.75f};
inline constexpr glm::vec4 kSharpCreaseColor{1.0f, 0.2f, 0.15f, 1.0f};
inline constexpr glm::vec4 kSemiSharpCreaseColor{1.0f, 0.55f, 0.1f, 1.0f};
inline constexpr glm::vec4 kCornerColor{0.2f, 0.9f, 1.0f, 1.0f};

class CageWireframe {
public:
    explicit CageWireframe(const mesh::PolygonMesh& cage);

    // Into the bound framebuffer and viewport, blended over what is there, without depth test:
    // the whole cage shows, also where it lies behind the surface.
    void draw(gl::ProgramCache& programs, const gl::Buffer& vertices, const render::Camera& camera) const;

private:
    // One primitive list of one colour.
    struct Part {
        GLenum primitive;
        glm::vec4 color;
        GLsizei count = 0;
        gl::Buffer indices{};
        gl::VertexArray vertexArray{};
    };
    void add(GLenum primitive, glm::vec4 color, const std::vector<unsigned>& indices);

    std::vector<Part> parts_;
};

}  // namespace subdfit::view
