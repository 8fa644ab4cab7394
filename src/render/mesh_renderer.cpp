#include "render/mesh_renderer.h"

#include "render/raster_pass.h"

namespace subdfit::render {

MeshRenderer::MeshRenderer(const std::vector<glm::vec3>& positions, const std::vector<glm::vec3>& normals,
                           const std::vector<unsigned>& triangleIndices)
    : indexCount_(GLsizei(triangleIndices.size())),
      positions_(gl::Buffer::fromVector(positions)),
      normals_(gl::Buffer::fromVector(normals)),
      indices_(gl::Buffer::fromVector(triangleIndices)) {
    GLuint id = 0;
    glCreateVertexArrays(1, &id);
    vertexArray_ = gl::GlHandle<gl::VertexArrayTraits>(id);
    glVertexArrayVertexBuffer(id, 0, positions_.id(), 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(id, 1, normals_.id(), 0, sizeof(glm::vec3));
    for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(id, a);
        glVertexArrayAttribFormat(id, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(id, a, a);
    }
    glVertexArrayElementBuffer(id, indices_.id());
}

void MeshRenderer::draw(gl::ProgramCache& programs, const Camera& camera, const RenderTarget& target) const {
    const auto& program = programs.get("mesh_raster", {{GL_VERTEX_SHADER, "mesh.vert"},
                                                       {GL_FRAGMENT_SHADER, "mesh.frag"}});
    beginRasterPass(program, camera, target);
    glBindVertexArray(vertexArray_.id());
    glDrawElements(GL_TRIANGLES, indexCount_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

}  // namespace subdfit::render
