#pragma once
// Draws a triangle mesh (the reference) with the same shading as the cage.
#include <glm/vec3.hpp>
#include <vector>

#include "gl/buffer.h"
#include "gl/program_cache.h"
#include "gl/vertex_array.h"
#include "render/camera.h"
#include "render/render_target.h"

namespace subdfit::render {

class MeshRenderer {
public:
    MeshRenderer(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                 const std::vector<unsigned>& triangleIndices);

    void draw(gl::ProgramCache& programs, const Camera& camera, const RenderTarget& target) const;

private:
    GLsizei indexCount_;
    gl::Buffer positions_, normals_, indices_;
    gl::VertexArray vertexArray_;
};

}  // namespace subdfit::render
